#include "lanelet2_osm_checks.hpp"

#include "mapfuse/core/error.hpp"

namespace mapfuse::io::detail {

void checkLanelet2Members(const std::vector<Lanelet2MemberRef>& members, const std::string& file,
                          const std::unordered_map<int64_t, geo::LatLonAlt>& nodes,
                          const Lanelet2Map& map) {
  for (const Lanelet2MemberRef& m : members) {
    const bool found = m.type == "node"       ? nodes.count(m.ref) > 0
                       : m.type == "way"      ? map.way(m.ref) != nullptr
                       : m.type == "relation" ? map.relation_ids.count(m.ref) > 0
                                              : true;  // unknown member types are not read
    if (!found)
      throw ParseError(file, m.where, m.type + " ref " + std::to_string(m.ref) + " does not exist");
  }
}

void checkLanelet2Bounds(const std::string& file, const Lanelet2Map& map) {
  for (const Lanelet2Lanelet& ll : map.lanelets)
    if (ll.left == ll.right)
      throw ParseError(file, "relation " + std::to_string(ll.id) + " member right",
                       "the right bound is way " + std::to_string(ll.right) +
                           ", the lanelet's left bound too (a lanelet without area)");
}

}  // namespace mapfuse::io::detail
