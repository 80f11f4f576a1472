#pragma once
/// @file Content checks of the Lanelet2 reader that need the whole map (docs/formats.md "Map
/// content checks"): every member of a lanelet or regulatory element exists, and no lanelet's
/// left bound is its right bound.
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "mapfuse/io/lanelet2_osm.hpp"

namespace mapfuse::io::detail {

/// A member of a lanelet or regulatory element, resolved once every relation is read (a member
/// may name a relation that comes later in the file).
struct Lanelet2MemberRef {
  std::string where;  ///< "relation <id> member <role>"
  std::string type;   ///< "node", "way" or "relation"
  int64_t ref = 0;
};

/// @brief Every node, way and relation a lanelet or regulatory element names exists (a dangling
/// reference is a map cut out of a larger one, or an edit gone wrong).
/// @throws ParseError naming the relation, the member's role and the missing element.
void checkLanelet2Members(const std::vector<Lanelet2MemberRef>& members, const std::string& file,
                          const std::unordered_map<int64_t, geo::LatLonAlt>& nodes,
                          const Lanelet2Map& map);

/// @brief No lanelet whose left bound is its right bound (Lanelet2's bounds enclose the
/// lanelet's area). @throws ParseError naming the lanelet.
void checkLanelet2Bounds(const std::string& file, const Lanelet2Map& map);

}  // namespace mapfuse::io::detail
