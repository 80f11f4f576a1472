#pragma once
/// @file Binary little-endian PLY of a labelled cloud that CloudCompare, PCL and Open3D read
/// whole: `element vertex N` with `float x, y, z; uchar red, green, blue; int scalar_label;
/// float scalar_confidence; int scalar_semantic_kitti` (colours from the LiDAR class palette,
/// RGB). `scalar_label` is mapfuse's LiDAR class id 0-7, `scalar_semantic_kitti` the
/// SemanticKITTI semantic id of that class (docs/formats.md "LiDAR classes"); the header's
/// comments say so. The `scalar_` prefix makes CloudCompare load them as scalar fields.
#include <filesystem>
#include <string>

#include "mapfuse/core/labeled_cloud.hpp"

namespace mapfuse::io {

/// @brief Writes the cloud atomically. @throws InputError for inconsistent array sizes.
void writePly(const std::filesystem::path& path, const LabeledCloud& cloud);

/// @brief Reads a binary little-endian PLY with vertex properties x, y, z (float or double)
/// and optional scalar_label or label (any integer type) and scalar_confidence or confidence
/// (float); other properties are skipped.
/// @throws IoError when unreadable; ParseError(file, field) for a malformed header, an
/// unsupported format or type, a missing x/y/z, a truncated body, a coordinate beyond
/// bounds::kMaxCoordinate, a label that is no LiDAR class id or a confidence outside [0, 1].
LabeledCloud readPly(const std::filesystem::path& path);
/// @brief The same from the bytes of a file; `file` names it in errors.
LabeledCloud parsePly(const std::string& bytes, const std::string& file);

}  // namespace mapfuse::io
