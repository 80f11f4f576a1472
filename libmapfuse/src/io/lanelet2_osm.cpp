#include "mapfuse/io/lanelet2_osm.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <pugixml.hpp>
#include <unordered_map>

#include "lanelet2_osm_checks.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/bounds.hpp"
#include "mapfuse/io/osm_sidecar.hpp"
#include "xml_root.hpp"

namespace mapfuse::io {

namespace {

// lanelet2_core/doc/LinestringTagging.md: lane boundaries, other boundaries and barriers,
// symbols on the road, signs and lights (plus `symbol`, which mapping tools write).
const char* const kKnownWayTypes[] = {"line_thin",
                                      "line_thick",
                                      "stop_line",
                                      "curbstone",
                                      "road_border",
                                      "zebra_marking",
                                      "pedestrian_marking",
                                      "bike_marking",
                                      "traffic_sign",
                                      "traffic_light",
                                      "virtual",
                                      "guard_rail",
                                      "wall",
                                      "fence",
                                      "keepout",
                                      "jersey_barrier",
                                      "gate",
                                      "door",
                                      "rail",
                                      "arrow",
                                      "zig-zag",
                                      "lift_gate",
                                      "bump",
                                      "symbol",
                                      "parking_space"};

// Node types that mark dash ends (LinestringTagging.md "Individual Dashes"), not map points.
bool isDashMarker(const std::string& type) {
  return type == "begin" || type == "end" || type == "start" || type == "dot";
}

/// Ids within +-(2^63 - 2^32): the simulator numbers the elements it adds (fewer than 2^32)
/// after the largest id. The Karlsruhe example map has ids up to 9.217e18, so int64 range it is.
constexpr long long kMaxId = std::numeric_limits<long long>::max() - (1LL << 32);

std::string elementName(const char* kind, int64_t id) {
  return std::string(kind) + " " + std::to_string(id);
}

int64_t parseId(const pugi::xml_node& n, const char* attr, const std::string& file,
                const std::string& where) {
  const pugi::xml_attribute a = n.attribute(attr);
  if (!a) throw ParseError(file, where, std::string("missing attribute '") + attr + "'");
  const char* s = a.value();
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(s, &end, 10);
  if (errno != 0 || end == s || *end != '\0')
    throw ParseError(file, where,
                     std::string("attribute '") + attr + "' = '" + s + "' is not an integer id");
  if (v < -kMaxId || v > kMaxId)
    throw ParseError(
        file, where,
        std::string("attribute '") + attr + "' = '" + s + "' is beyond +-(2^63 - 2^32)");
  return v;
}

double parseCoordinate(const pugi::xml_node& n, const char* attr, double limit,
                       const std::string& file, const std::string& where) {
  const pugi::xml_attribute a = n.attribute(attr);
  if (!a) throw ParseError(file, where + " " + attr, "missing");
  const char* s = a.value();
  char* end = nullptr;
  const double v = std::strtod(s, &end);
  if (end == s || *end != '\0' || !std::isfinite(v))
    throw ParseError(file, where + " " + attr, std::string("'") + s + "' is not a number");
  if (std::abs(v) > limit)
    throw ParseError(file, where + " " + attr,
                     std::string("'") + s + "' is out of range [-" +
                         std::to_string(static_cast<int>(limit)) + ", " +
                         std::to_string(static_cast<int>(limit)) + "]");
  return v;
}

std::map<std::string, std::string> readTags(const pugi::xml_node& n) {
  std::map<std::string, std::string> tags;
  for (const pugi::xml_node t : n.children("tag"))
    tags[t.attribute("k").value()] = t.attribute("v").value();
  return tags;
}

std::string tagOr(const std::map<std::string, std::string>& tags, const std::string& key,
                  const std::string& fallback) {
  const auto it = tags.find(key);
  return it == tags.end() ? fallback : it->second;
}

}  // namespace

bool isKnownLanelet2WayType(const std::string& type) {
  for (const char* k : kKnownWayTypes)
    if (type == k) return true;
  return false;
}

int Lanelet2Map::countWays(const std::string& type, const std::string& subtype) const {
  int n = 0;
  for (const auto& w : linestrings)
    if (w.type == type && (subtype.empty() || w.subtype == subtype)) ++n;
  return n;
}

const Lanelet2LineString* Lanelet2Map::way(int64_t id) const {
  const auto it = way_index.find(id);
  return it == way_index.end() ? nullptr : &linestrings[it->second];
}

namespace {
/// The nodes (id -> position); tagged points (poles, ...) go to map.points.
std::unordered_map<int64_t, geo::LatLonAlt> readNodes(const pugi::xml_node& osm,
                                                      const std::string& file, Lanelet2Map& map) {
  std::unordered_map<int64_t, geo::LatLonAlt> nodes;
  for (const pugi::xml_node n : osm.children("node")) {
    const int64_t id = parseId(n, "id", file, "node");
    const std::string where = elementName("node", id);
    if (std::string(n.attribute("action").value()) == "delete") continue;
    geo::LatLonAlt p;
    p.lat = parseCoordinate(n, "lat", 90.0, file, where);
    p.lon = parseCoordinate(n, "lon", 180.0, file, where);
    const auto tags = readTags(n);
    const auto ele = tags.find("ele");
    if (ele != tags.end()) {
      char* end = nullptr;
      p.alt = std::strtod(ele->second.c_str(), &end);
      if (end == ele->second.c_str() || *end != '\0' || !std::isfinite(p.alt))
        throw ParseError(file, where + " ele", "'" + ele->second + "' is not a number");
      if (!bounds::within(p.alt, bounds::kMinAltitude, bounds::kMaxAltitude))
        throw ParseError(file, where + " ele",
                         "'" + ele->second + "' m is outside " +
                             bounds::rangeText(bounds::kMinAltitude, bounds::kMaxAltitude));
    }
    if (!nodes.emplace(id, p).second) throw ParseError(file, where, "duplicate node id");
    if (!map.first_node) map.first_node = p;
    const auto type = tags.find("type");
    if (type != tags.end() && !isDashMarker(type->second))
      map.points.push_back({id, type->second, tags, p});
  }
  return nodes;
}

/// The ways as line strings of the nodes they reference, typed by their tags.
void readWays(const pugi::xml_node& osm, const std::string& file,
              const std::unordered_map<int64_t, geo::LatLonAlt>& nodes, Lanelet2Map& map) {
  for (const pugi::xml_node w : osm.children("way")) {
    Lanelet2LineString ls;
    ls.id = parseId(w, "id", file, "way");
    const std::string where = elementName("way", ls.id);
    if (std::string(w.attribute("action").value()) == "delete") continue;
    for (const pugi::xml_node nd : w.children("nd")) {
      const int64_t ref = parseId(nd, "ref", file, where + " nd");
      const auto it = nodes.find(ref);
      if (it == nodes.end())
        throw ParseError(file, where, "node ref " + std::to_string(ref) + " does not exist");
      ls.node_ids.push_back(ref);
      ls.points.push_back(it->second);
    }
    if (ls.points.empty()) throw ParseError(file, where, "way has no nodes");
    ls.tags = readTags(w);
    ls.type = tagOr(ls.tags, "type", "");
    ls.subtype = tagOr(ls.tags, "subtype", "");
    if (ls.type.empty()) {  // CommonRoad conversions: a bound without type is no marking
      ls.type = "virtual";
      ls.untyped = true;
      ++map.untyped_ways;
    }
    ls.known_type = isKnownLanelet2WayType(ls.type);
    if (!ls.known_type) ++map.skipped_way_types[ls.type];
    if (!map.way_index.emplace(ls.id, map.linestrings.size()).second)
      throw ParseError(file, where, "duplicate way id");
    map.linestrings.push_back(std::move(ls));
  }
}

/// The relations: lanelets with their bounds, regulatory elements; other types are counted.
/// @return the members of lanelets and regulatory elements, for checkMembers.
std::vector<detail::Lanelet2MemberRef> readRelations(const pugi::xml_node& osm,
                                                     const std::string& file, Lanelet2Map& map) {
  std::vector<detail::Lanelet2MemberRef> members;
  for (const pugi::xml_node r : osm.children("relation")) {
    const int64_t id = parseId(r, "id", file, "relation");
    const std::string where = elementName("relation", id);
    if (std::string(r.attribute("action").value()) == "delete") continue;
    if (!map.relation_ids.insert(id).second) throw ParseError(file, where, "duplicate relation id");
    const auto tags = readTags(r);
    const std::string type = tagOr(tags, "type", "");
    if (type == "lanelet" || type == "regulatory_element")
      for (const pugi::xml_node m : r.children("member"))
        members.push_back({where + " member " + m.attribute("role").value(),
                           m.attribute("type").value(),
                           parseId(m, "ref", file, where + " member")});
    if (type == "lanelet") {
      Lanelet2Lanelet ll;
      ll.id = id;
      ll.subtype = tagOr(tags, "subtype", "");
      const std::string one_way = tagOr(tags, "one_way", "yes");
      ll.one_way = !(one_way == "no" || one_way == "false");
      bool has_left = false, has_right = false;
      for (const pugi::xml_node m : r.children("member")) {
        const std::string role = m.attribute("role").value();
        const std::string mtype = m.attribute("type").value();
        const int64_t ref = parseId(m, "ref", file, where + " member");
        if (role == "regulatory_element") {
          ll.regulatory_elements.push_back(ref);
          continue;
        }
        if (role != "left" && role != "right") continue;
        if (mtype != "way")
          throw ParseError(file, where + " " + role, "bound must be a way, got '" + mtype + "'");
        if (!map.way(ref))
          throw ParseError(file, where + " " + role,
                           "way ref " + std::to_string(ref) + " does not exist");
        if (map.way(ref)->points.size() < 2)
          throw ParseError(file, where + " " + role, "bound way has fewer than 2 nodes");
        (role == "left" ? ll.left : ll.right) = ref;
        (role == "left" ? has_left : has_right) = true;
      }
      if (!has_left || !has_right)
        throw ParseError(
            file, where,
            std::string("lanelet lacks its ") + (has_left ? "right" : "left") + " bound");
      map.lanelets.push_back(ll);
    } else if (type == "regulatory_element") {
      Lanelet2Regulatory re;
      re.id = id;
      re.subtype = tagOr(tags, "subtype", "");
      for (const pugi::xml_node m : r.children("member")) {
        const std::string role = m.attribute("role").value();
        const std::string mtype = m.attribute("type").value();
        if (mtype == "relation" && (role == "yield" || role == "right_of_way")) {
          const int64_t ref = parseId(m, "ref", file, where + " member");
          (role == "yield" ? re.yield : re.right_of_way).push_back(ref);
          continue;
        }
        if (mtype != "way") continue;
        const int64_t ref = parseId(m, "ref", file, where + " member");
        if (role == "refers") re.refers.push_back(ref);
        if (role == "ref_line") re.ref_lines.push_back(ref);
      }
      map.regulatory_elements.push_back(re);
    } else {
      ++map.skipped_relation_types[type.empty() ? "(none)" : type];
    }
  }
  return members;
}

}  // namespace

Lanelet2Map parseLanelet2Osm(const std::string& xml, const std::string& file) {
  pugi::xml_document doc;
  const pugi::xml_node osm = detail::xmlRoot(doc, xml, file, "osm");
  Lanelet2Map map;
  map.file = file;
  const auto nodes = readNodes(osm, file, map);
  map.node_count = nodes.size();
  readWays(osm, file, nodes, map);
  detail::checkLanelet2Members(readRelations(osm, file, map), file, nodes, map);
  detail::checkLanelet2Bounds(file, map);
  return map;
}

Lanelet2Map readLanelet2Osm(const std::filesystem::path& path) {
  const std::string xml = readBytes(path);
  Lanelet2Map map = parseLanelet2Osm(xml, path.string());
  applyOsmSidecar(path, xml, map);
  return map;
}

}  // namespace mapfuse::io
