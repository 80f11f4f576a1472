#pragma once
/// @file One line of a KITTI OXTS file (oxts/data/<frame>.txt): 30 numbers in the order of
/// oxts/dataformat.txt, read with the range checks of docs/formats.md "Value bounds".
/// The pose conventions of the record are in geo/oxts.hpp; writing is io::formatOxtsLine
/// (io/kitti_raw_writer.hpp).
#include <string>

#include "mapfuse/geo/oxts.hpp"

namespace mapfuse::io {

/// @brief Parses one OXTS text line (30 whitespace-separated numbers), each within its range of
/// docs/formats.md "Value bounds" (|lat| <= 85 deg for the Mercator pose, the status fields
/// integers). @throws ParseError naming `file` and the field that is missing, not a number or
/// out of range.
geo::OxtsRecord parseOxtsLine(const std::string& line, const std::string& file);

}  // namespace mapfuse::io
