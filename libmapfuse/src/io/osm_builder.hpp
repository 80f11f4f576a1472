#pragma once
/// @file The OSM XML document of a Lanelet2 export being built (io/osm_export.cpp): elements in
/// Lanelet2's order (nodes, ways, relations), ids negative and unique across the file as
/// Lanelet2 and JOSM write new elements; nearby plain nodes shared.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <pugixml.hpp>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "mapfuse/geo/origin.hpp"

namespace mapfuse::io::detail {

// m: Lanelet2's validator warns about any two points of a map closer than 0.05 m
// (mapping.points_too_close, 3D, measured in its UTM frame, whose scale is 0.9996-1.001 of the
// ENU metres: two nodes 0.0500 m apart in ENU were 0.0499 m apart there); plain nodes closer
// than 0.05 m with 0.4 % margin share one node instead (moving a point by at most that)
constexpr double kNodeMerge = 0.0502;

using V3 = Eigen::Vector3d;
using Tags = std::vector<std::pair<std::string, std::string>>;

inline std::string fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.*f", decimals, v);
  return buf;
}

struct Member {
  const char* type;
  int64_t ref;
  std::string role;
};

/// The document being built.
class OsmBuilder {
 public:
  explicit OsmBuilder(const geo::GeoOrigin& origin) : enu_(origin) {
    auto decl = doc_.append_child(pugi::node_declaration);
    decl.append_attribute("version") = "1.0";
    decl.append_attribute("encoding") = "UTF-8";
    osm_ = doc_.append_child("osm");
    osm_.append_attribute("version") = "0.6";
    osm_.append_attribute("generator") = "mapfuse";
    ways_ = osm_.append_child("way");  // placeholders keep the element order; removed at the end
    relations_ = osm_.append_child("relation");
  }

  int64_t node(const V3& p, const Tags& tags = {}) {
    const geo::LatLonAlt g = enu_.toWgs84(p);
    auto n = osm_.insert_child_before("node", ways_);
    const int64_t id = next_--;
    n.append_attribute("id") = static_cast<long long>(id);
    n.append_attribute("lat") = fixed(g.lat, 10).c_str();
    n.append_attribute("lon") = fixed(g.lon, 10).c_str();
    tag(n, "ele", fixed(g.alt, 3));
    for (const auto& [k, v] : tags) tag(n, k, v);
    return id;
  }

  /// A plain node at p, or an earlier plain node within kNodeMerge of it (a 3D grid of
  /// kNodeMerge cells, the 27 around p searched).
  int64_t sharedNode(const V3& p) {
    const auto cell = [](double v) { return static_cast<int64_t>(std::floor(v / kNodeMerge)); };
    const int64_t cx = cell(p.x()), cy = cell(p.y()), cz = cell(p.z());
    for (int64_t dx = -1; dx <= 1; ++dx)
      for (int64_t dy = -1; dy <= 1; ++dy)
        for (int64_t dz = -1; dz <= 1; ++dz) {
          const auto it = nodes_.find({cx + dx, cy + dy, cz + dz});
          if (it == nodes_.end()) continue;
          for (const auto& [id, q] : it->second)
            if ((q - p).norm() < kNodeMerge) return id;
        }
    const int64_t id = node(p);
    nodes_[{cx, cy, cz}].push_back({id, p});
    return id;
  }

  /// A way through `nodes`; a node repeated right after itself (points merged by sharedNode)
  /// is written once.
  int64_t way(const std::vector<int64_t>& nodes, const Tags& tags) {
    auto w = osm_.insert_child_before("way", relations_);
    const int64_t id = next_--;
    w.append_attribute("id") = static_cast<long long>(id);
    for (std::size_t i = 0; i < nodes.size(); ++i)
      if (i == 0 || nodes[i] != nodes[i - 1])
        w.append_child("nd").append_attribute("ref") = static_cast<long long>(nodes[i]);
    for (const auto& [k, v] : tags) tag(w, k, v);
    return id;
  }

  /// A way through plain nodes at `points` (an earlier plain node within kNodeMerge is shared;
  /// way() writes consecutive points that fall on one node once); `closed` repeats the first
  /// node at the end. A way whose points all fall on one node keeps nodes of its own.
  int64_t way(const std::vector<V3>& points, const Tags& tags, bool closed = false) {
    std::vector<int64_t> ids;
    for (const auto& p : points) ids.push_back(sharedNode(p));
    if (points.size() >= 2 && std::count(ids.begin(), ids.end(), ids.front()) == long(ids.size())) {
      ids.clear();
      for (const auto& p : points) ids.push_back(node(p));
    }
    if (closed && ids.size() > 1 && ids.back() != ids.front()) ids.push_back(ids.front());
    return way(ids, tags);
  }

  /// An id for an element written later (relations that refer to each other).
  int64_t reserve() { return next_--; }

  /// A relation; `id` 0: a new id, else one from reserve().
  int64_t relation(const std::vector<Member>& members, const Tags& tags, int64_t id = 0) {
    auto r = osm_.append_child("relation");
    if (id == 0) id = next_--;
    r.append_attribute("id") = static_cast<long long>(id);
    for (const auto& m : members) {
      auto x = r.append_child("member");
      x.append_attribute("type") = m.type;
      x.append_attribute("ref") = static_cast<long long>(m.ref);
      x.append_attribute("role") = m.role.c_str();
    }
    for (const auto& [k, v] : tags) tag(r, k, v);
    return id;
  }

  std::string xml() {
    osm_.remove_child(ways_);
    osm_.remove_child(relations_);
    std::ostringstream out;
    doc_.save(out, "  ", pugi::format_default, pugi::encoding_utf8);
    return out.str();
  }

 private:
  static void tag(pugi::xml_node n, const std::string& k, const std::string& v) {
    auto t = n.append_child("tag");
    t.append_attribute("k") = k.c_str();
    t.append_attribute("v") = v.c_str();
  }

  geo::EnuConverter enu_;
  std::map<std::array<int64_t, 3>, std::vector<std::pair<int64_t, V3>>> nodes_;
  pugi::xml_document doc_;
  pugi::xml_node osm_, ways_, relations_;
  int64_t next_ = -1;
};

}  // namespace mapfuse::io::detail
