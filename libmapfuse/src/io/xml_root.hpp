#pragma once
/// @file The XML map readers' first step (Lanelet2 OSM, OpenDRIVE): parse the text, check that
/// it is UTF-8 and find its root element, with errors naming the file.
#include <pugixml.hpp>
#include <string>

#include "mapfuse/core/error.hpp"
#include "utf8.hpp"

namespace mapfuse::io::detail {

/// @brief Every element name, attribute (name and value) and text of `doc` is UTF-8. pugixml
/// converts the encodings it knows (UTF-16 and -32, a declared Latin-1) to UTF-8 but passes the
/// stray bytes of a UTF-8 file through, and such text kept in a note or an input warning made
/// the JSON writers throw later: simulate exit 1 (fuzz_opendrive_drive, issue 37).
/// @throws ParseError naming the element and attribute (when they are UTF-8 themselves) and the
/// element's byte offset.
inline void requireUtf8(pugi::xml_document& doc, const std::string& file) {
  struct Walker : pugi::xml_tree_walker {
    std::string field;  // empty while every text seen is UTF-8
    std::ptrdiff_t offset = 0;
    bool for_each(pugi::xml_node& node) override {
      const bool element = node.type() == pugi::node_element;
      const std::string name = validUtf8(node.name()) ? node.name() : "(element)";
      if (element && !validUtf8(node.name())) return fail(node, name);
      if (!element && !validUtf8(node.value()))  // text: its element was checked before
        return fail(node.parent(), std::string(node.parent().name()) + " text");
      for (const pugi::xml_attribute& a : node.attributes())
        if (!validUtf8(a.name()) || !validUtf8(a.value()))
          return fail(node, name + "@" + (validUtf8(a.name()) ? a.name() : "(attribute)"));
      return true;
    }
    bool fail(const pugi::xml_node& node, const std::string& what) {
      field = what, offset = node.offset_debug();
      return false;  // stops the walk
    }
  } walker;
  doc.traverse(walker);
  if (!walker.field.empty())
    throw ParseError(file, walker.field,
                     "text that is not UTF-8 (element at byte offset " +
                         std::to_string(walker.offset) + ")");
}

/// @brief Parses `xml` into `doc` and returns its root element named `root`.
/// @throws ParseError naming `file` and the byte offset of a syntax error, text that is not
/// UTF-8 (requireUtf8), or the missing root.
inline pugi::xml_node xmlRoot(pugi::xml_document& doc, const std::string& xml,
                              const std::string& file, const char* root) {
  const pugi::xml_parse_result ok = doc.load_buffer(xml.data(), xml.size());
  if (!ok)
    throw ParseError(
        file, "",
        std::string("XML: ") + ok.description() + " at byte offset " + std::to_string(ok.offset));
  requireUtf8(doc, file);
  const pugi::xml_node node = doc.child(root);
  if (!node) throw ParseError(file, root, std::string("no <") + root + "> root element");
  return node;
}

}  // namespace mapfuse::io::detail
