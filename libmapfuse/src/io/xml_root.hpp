#pragma once
/// @file The XML map readers' first step (Lanelet2 OSM, OpenDRIVE): parse the text and find its
/// root element, with errors naming the file.
#include <pugixml.hpp>
#include <string>

#include "mapfuse/core/error.hpp"

namespace mapfuse::io::detail {

/// @brief Parses `xml` into `doc` and returns its root element named `root`.
/// @throws ParseError naming `file` and the byte offset of a syntax error, or the missing root.
inline pugi::xml_node xmlRoot(pugi::xml_document& doc, const std::string& xml,
                              const std::string& file, const char* root) {
  const pugi::xml_parse_result ok = doc.load_buffer(xml.data(), xml.size());
  if (!ok)
    throw ParseError(
        file, "",
        std::string("XML: ") + ok.description() + " at byte offset " + std::to_string(ok.offset));
  const pugi::xml_node node = doc.child(root);
  if (!node) throw ParseError(file, root, std::string("no <") + root + "> root element");
  return node;
}

}  // namespace mapfuse::io::detail
