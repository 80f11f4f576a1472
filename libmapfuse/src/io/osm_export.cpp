#include "mapfuse/io/osm_export.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <pugixml.hpp>
#include <sstream>

#include "mapfuse/geo/origin.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/lanelet2_right_of_way.hpp"

namespace mapfuse::io {
namespace {

constexpr double kLightWidth = 0.3;        // m, the light's line string across the approach
constexpr double kStopSample = 0.5;        // m between stop-line samples tested against lanelets
constexpr double kRegulatoryReach = 25.0;  // m from a stop line's middle to its lights / signs
constexpr double kLightBehind = 5.0;       // m a light may stand before its stop line
constexpr double kSignBehind = 15.0;       // m a sign may stand before its stop line
constexpr double kLoneReach = 15.0;        // m to the lanelet of a light or sign without stop line
// m: Lanelet2's validator warns about any two points of a map closer than this
// (mapping.points_too_close); plain nodes that close share one node instead
constexpr double kNodeMerge = 0.05;

using V3 = Eigen::Vector3d;
using Tags = std::vector<std::pair<std::string, std::string>>;

std::string fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.*f", decimals, v);
  return buf;
}

struct Member {
  const char* type;
  int64_t ref;
  std::string role;
};

/// The document being built: elements in Lanelet2's order (nodes, ways, relations), ids
/// negative and unique across the file as Lanelet2 and JOSM write new elements.
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

Tags laneLineTags(const MapInstance& m) {
  Tags t = {{"type", "line_thin"},
            {"subtype", m.attributes.style == LineStyle::kDashed ? "dashed" : "solid"}};
  if (m.attributes.color != LineColor::kNone)
    t.push_back({"color", lineColorName(m.attributes.color)});
  t.push_back({"mapfuse_id", std::to_string(m.id)});
  return t;
}

Tags idTag(const MapInstance& m, Tags t) {
  t.push_back({"mapfuse_id", std::to_string(m.id)});
  return t;
}

/// Unit xy direction of a lanelet's centre near point p (its travel direction when known).
Eigen::Vector2d directionNear(const LaneletPlan::Lanelet& ll, const V3& p) {
  std::size_t best = 0;
  for (std::size_t k = 0; k + 1 < ll.centre.size(); ++k)
    if ((ll.centre[k] - p).head<2>().norm() < (ll.centre[best] - p).head<2>().norm()) best = k;
  best = std::min(best, ll.centre.size() - 2);
  const Eigen::Vector2d d = (ll.centre[best + 1] - ll.centre[best]).head<2>();
  return d.norm() > 1e-9 ? Eigen::Vector2d(d.normalized()) : Eigen::Vector2d(1, 0);
}

double distanceToCentre(const LaneletPlan::Lanelet& ll, const V3& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& c : ll.centre) best = std::min(best, (c - p).head<2>().norm());
  return best;
}

/// Splits a crosswalk outline into two bounds: its longest edge and the opposite chain, so that
/// left + reversed(right) gives the outline back.
std::pair<std::vector<V3>, std::vector<V3>> crosswalkBounds(const std::vector<V3>& ring) {
  const std::size_t n = ring.size();
  std::size_t p = 0;
  for (std::size_t k = 1; k < n; ++k)
    if ((ring[(k + 1) % n] - ring[k]).head<2>().norm() >
        (ring[(p + 1) % n] - ring[p]).head<2>().norm())
      p = k;
  std::vector<V3> left = {ring[p], ring[(p + 1) % n]}, right;
  for (std::size_t k = 2; k < n; ++k) right.push_back(ring[(p + k) % n]);
  std::reverse(right.begin(), right.end());
  if (right.size() == 1) right.push_back(right.front());  // a triangle: a degenerate bound
  return {left, right};
}

}  // namespace

std::string vectorMapToOsm(const VectorMap& map, const std::vector<DrivePath>& drives,
                           Lanelet2ExportStats* stats_out) {
  Lanelet2ExportStats stats;
  const LaneletPlan plan = planLanelets(map, drives);
  OsmBuilder osm(map.origin);

  // Lane lines: the planned ones piece by piece (shared cut nodes), the others whole.
  std::map<std::size_t, std::size_t> plan_line_of;  // instance -> plan line
  for (std::size_t l = 0; l < plan.lines.size(); ++l) plan_line_of[plan.lines[l].instance] = l;
  std::vector<int64_t> piece_way(plan.pieces.size(), 0);
  std::vector<std::pair<int64_t, int64_t>> piece_nodes(plan.pieces.size());  // first, last
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> piece_of;       // (line, cut) -> piece
  for (std::size_t k = 0; k < plan.pieces.size(); ++k)
    piece_of[{plan.pieces[k].line, plan.pieces[k].cut}] = k;
  std::vector<double> instance_bound_m(map.instances.size(), 0.0);
  std::vector<bool> is_bound(plan.pieces.size(), false);
  for (const auto& ll : plan.lanelets) is_bound[ll.left] = is_bound[ll.right] = true;
  for (std::size_t i = 0; i < map.instances.size(); ++i) {
    const MapInstance& m = map.instances[i];
    if (m.cls != CrowdClass::kLaneLine) continue;
    stats.lane_line_m += polylineLength(m.points);
    const auto pl = plan_line_of.find(i);
    if (pl == plan_line_of.end()) {
      osm.way(m.points, laneLineTags(m));
      continue;
    }
    const auto& line = plan.lines[pl->second];
    std::vector<int64_t> nodes;
    for (const auto& p : line.points) nodes.push_back(osm.sharedNode(p));
    for (std::size_t c = 0; c + 1 < line.cuts.size(); ++c) {
      const int64_t w =
          osm.way(std::vector<int64_t>(nodes.begin() + static_cast<long>(line.cuts[c]),
                                       nodes.begin() + static_cast<long>(line.cuts[c + 1]) + 1),
                  laneLineTags(m));
      const auto pc = piece_of.find({pl->second, c});
      if (pc == piece_of.end()) continue;
      piece_way[pc->second] = w;
      piece_nodes[pc->second] = {nodes[line.cuts[c]], nodes[line.cuts[c + 1]]};
      if (is_bound[pc->second]) stats.bound_m += polylineLength(piecePoints(plan, pc->second));
    }
  }

  // Stop lines, arrows, poles, crosswalks.
  std::map<std::size_t, int64_t> stop_way;
  for (std::size_t i = 0; i < map.instances.size(); ++i) {
    const MapInstance& m = map.instances[i];
    switch (m.cls) {
      case CrowdClass::kStopLine:
        stop_way[i] = osm.way(m.points, idTag(m, {{"type", "stop_line"}}));
        break;
      case CrowdClass::kGroundArrow: osm.way(m.points, idTag(m, {{"type", "arrow"}}), true); break;
      case CrowdClass::kPole:
        osm.node(m.points.front(), idTag(m, {{"type", "pole"}, {"height", fixed(m.height, 3)}}));
        break;
      case CrowdClass::kCrosswalk: {
        const auto [left, right] = crosswalkBounds(m.points);
        const int64_t l = osm.way(left, idTag(m, {{"type", "zebra_marking"}}));
        const int64_t r = osm.way(right, idTag(m, {{"type", "zebra_marking"}}));
        osm.relation({{"way", l, "left"}, {"way", r, "right"}}, idTag(m, {{"type", "lanelet"},
                                                                          {"subtype", "crosswalk"},
                                                                          {"location", "urban"},
                                                                          {"one_way", "no"}}));
        ++stats.crosswalk_lanelets;
        break;
      }
      default: break;
    }
  }

  // Stop lines across lanelets, and the approach direction there.
  struct StopLine {
    std::size_t instance;
    V3 mid;
    std::vector<std::size_t> lanelets;
    Eigen::Vector2d approach = Eigen::Vector2d::Zero();
    std::vector<int64_t> lights, signs;
  };
  std::vector<StopLine> stop_lines;
  for (const auto& [i, w] : stop_way) {
    (void)w;
    const auto& pts = map.instances[i].points;
    StopLine st{i, 0.5 * (pts.front() + pts.back()), {}, {}, {}, {}};
    std::vector<V3> samples;
    for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
      const int n =
          std::max(1, static_cast<int>(std::ceil((pts[k + 1] - pts[k]).norm() / kStopSample)));
      for (int q = 0; q <= n; ++q) samples.push_back(pts[k] + (pts[k + 1] - pts[k]) * q / n);
    }
    for (std::size_t l = 0; l < plan.lanelets.size(); ++l) {
      const auto& ll = plan.lanelets[l];
      for (const auto& s : samples)
        if (insideRingXY(ll.ring, s)) {
          st.lanelets.push_back(l);
          if (ll.direction_known) st.approach += directionNear(ll, s);
          break;
        }
    }
    if (st.approach.norm() > 1e-9) st.approach.normalize();
    stop_lines.push_back(st);
  }

  // Lights and signs: line strings with height, tied to the nearest stop line they serve.
  std::vector<std::vector<int64_t>> lanelet_regs(plan.lanelets.size());
  auto nearestStop = [&](const V3& p, double behind) -> StopLine* {
    StopLine* best = nullptr;
    double best_d = kRegulatoryReach;
    for (auto& st : stop_lines) {
      const double d = (p - st.mid).head<2>().norm();
      if (d > best_d || st.lanelets.empty()) continue;
      if (st.approach.norm() > 0 && st.approach.dot((p - st.mid).head<2>()) < -behind) continue;
      best = &st;
      best_d = d;
    }
    return best;
  };
  auto nearestLanelet = [&](const V3& p) -> long {
    long best = -1;
    double best_d = kLoneReach;
    for (std::size_t l = 0; l < plan.lanelets.size(); ++l) {
      const double d = distanceToCentre(plan.lanelets[l], p);
      if (d < best_d) best = static_cast<long>(l), best_d = d;
    }
    return best;
  };
  auto lone = [&](int64_t way, const V3& p, const char* subtype) {
    const long l = nearestLanelet(p);
    const int64_t r = osm.relation({{"way", way, "refers"}},
                                   {{"type", "regulatory_element"}, {"subtype", subtype}});
    ++stats.regulatory_elements;
    if (l >= 0) lanelet_regs[static_cast<std::size_t>(l)].push_back(r);
  };
  for (const MapInstance& m : map.instances) {
    if (m.cls == CrowdClass::kTrafficLight) {
      const V3 c = m.points.front();
      StopLine* st = nearestStop(c, kLightBehind);
      Eigen::Vector2d across(1, 0);
      if (st && st->approach.norm() > 0) {
        across = {-st->approach.y(), st->approach.x()};
      } else if (const long l = nearestLanelet(c); l >= 0) {
        const Eigen::Vector2d d = directionNear(plan.lanelets[static_cast<std::size_t>(l)], c);
        across = {-d.y(), d.x()};
      }
      const V3 half = 0.5 * kLightWidth * V3(across.x(), across.y(), 0.0);
      const int64_t w =
          osm.way({c - half, c + half},
                  idTag(m, {{"type", "traffic_light"}, {"height", fixed(m.height, 3)}}));
      if (st)
        st->lights.push_back(w);
      else
        lone(w, c, "traffic_light");
    } else if (m.cls == CrowdClass::kTrafficSign) {
      // The plate's bottom edge: its two lowest corners, with the plate's height.
      std::vector<V3> corners = m.points;
      std::vector<std::size_t> order(corners.size());
      for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
      std::sort(order.begin(), order.end(),
                [&](std::size_t a, std::size_t b) { return corners[a].z() < corners[b].z(); });
      const std::size_t a = std::min(order[0], order[1]), b = std::max(order[0], order[1]);
      double top = corners.front().z();
      for (const auto& q : corners) top = std::max(top, q.z());
      const double height = top - 0.5 * (corners[a].z() + corners[b].z());
      const int64_t w = osm.way(
          {corners[a], corners[b]},
          // Lanelet2 refuses a traffic_sign regulatory element whose sign has no subtype
          // (the sign's code, "de205"): the crowd map does not classify signs, so "unknown"
          idTag(m,
                {{"type", "traffic_sign"}, {"subtype", "unknown"}, {"height", fixed(height, 3)}}));
      const V3 c = 0.5 * (corners[a] + corners[b]);
      if (StopLine* st = nearestStop(c, kSignBehind))
        st->signs.push_back(w);
      else
        lone(w, c, "traffic_sign");
    }
  }
  for (const auto& st : stop_lines) {
    const int64_t line = stop_way.at(st.instance);
    for (const auto& [refs, subtype] :
         {std::make_pair(st.lights, "traffic_light"), std::make_pair(st.signs, "traffic_sign")}) {
      if (refs.empty()) continue;
      std::vector<Member> members;
      for (int64_t w : refs) members.push_back({"way", w, "refers"});
      members.push_back({"way", line, "ref_line"});
      const int64_t r =
          osm.relation(members, {{"type", "regulatory_element"}, {"subtype", subtype}});
      ++stats.regulatory_elements;
      for (std::size_t l : st.lanelets) lanelet_regs[l].push_back(r);
    }
  }

  // Right of way at intersections with stop lines (io/lanelet2_right_of_way.hpp). Lanelets and
  // these elements refer to each other, so both ids are reserved first: lanelets, then the
  // elements, written in that order (osmium expects relations in id order).
  std::vector<int64_t> lanelet_id(plan.lanelets.size());
  for (auto& id : lanelet_id) id = osm.reserve();
  // A stop line is signalled when a light stands within reach of it, whether or not the light
  // was tied to it above (that needs a lanelet across the stop line).
  std::vector<RightOfWayStop> stops;
  for (const auto& st : stop_lines) {
    bool lit = !st.lights.empty();
    for (const MapInstance& m : map.instances)
      lit |= m.cls == CrowdClass::kTrafficLight &&
             (m.points.front() - st.mid).head<2>().norm() <= kRegulatoryReach;
    stops.push_back({map.instances[st.instance].points, lit});
  }
  const std::vector<RightOfWayRule> rules = deriveRightOfWay(plan, stops, drives);
  std::vector<int64_t> rule_id(rules.size());
  for (std::size_t k = 0; k < rules.size(); ++k) {
    rule_id[k] = osm.reserve();
    for (const auto* group : {&rules[k].yield, &rules[k].right_of_way})
      for (std::size_t l : *group) lanelet_regs[l].push_back(rule_id[k]);
  }

  // Road lanelets.
  for (std::size_t l = 0; l < plan.lanelets.size(); ++l) {
    const auto& ll = plan.lanelets[l];
    std::vector<Member> members = {{"way", piece_way[ll.left], "left"},
                                   {"way", piece_way[ll.right], "right"}};
    for (int64_t r : lanelet_regs[l]) members.push_back({"relation", r, "regulatory_element"});
    osm.relation(members,
                 {{"type", "lanelet"},
                  {"subtype", "road"},
                  {"location", "urban"},
                  {"one_way", ll.direction_known ? "yes" : "no"}},
                 lanelet_id[l]);
    ++stats.lanelets;
    stats.lanelets_direction_known += ll.direction_known;
    stats.lanelets_with_regulatory += !lanelet_regs[l].empty();
  }
  for (std::size_t k = 0; k < rules.size(); ++k) {
    const RightOfWayRule& rule = rules[k];
    std::vector<Member> members;
    for (std::size_t l : rule.yield) members.push_back({"relation", lanelet_id[l], "yield"});
    for (std::size_t l : rule.right_of_way)
      members.push_back({"relation", lanelet_id[l], "right_of_way"});
    if (rule.all_way_stop)  // the signs at the stop lines constitute the rule
      for (std::size_t s : rule.yield_stop)
        for (int64_t w : stop_lines[s].signs) members.push_back({"way", w, "refers"});
    for (std::size_t s : rule.yield_stop)  // in the order of the yield lanelets
      members.push_back({"way", stop_way.at(stop_lines[s].instance), "ref_line"});
    osm.relation(members,
                 {{"type", "regulatory_element"},
                  {"subtype", rule.all_way_stop ? "all_way_stop" : "right_of_way"}},
                 rule_id[k]);
    ++(rule.all_way_stop ? stats.all_way_stop_elements : stats.right_of_way_elements);
  }
  // Connectors across intersections: `virtual` bounds sharing the end nodes of the lanelets they
  // join, so that Lanelet2's routing finds the way through.
  for (const auto& c : plan.connectors) {
    std::vector<Member> members;
    for (const bool left : {true, false}) {
      const auto [pa, a_last] = boundEnd(plan, plan.lanelets[c.from], left, true);
      const auto [pb, b_last] = boundEnd(plan, plan.lanelets[c.to], left, false);
      const auto& pts = left ? c.left : c.right;
      std::vector<int64_t> nodes = {a_last ? piece_nodes[pa].second : piece_nodes[pa].first};
      for (std::size_t k = 1; k + 1 < pts.size(); ++k) nodes.push_back(osm.sharedNode(pts[k]));
      nodes.push_back(b_last ? piece_nodes[pb].second : piece_nodes[pb].first);
      members.push_back({"way", osm.way(nodes, {{"type", "virtual"}}), left ? "left" : "right"});
    }
    osm.relation(members, {{"type", "lanelet"},
                           {"subtype", "road"},
                           {"location", "urban"},
                           {"one_way", "yes"},
                           {"mapfuse:connector", std::to_string(c.drives) + " drives"}});
    ++stats.connector_lanelets;
  }
  stats.unmatched_pieces = plan.unmatched_pieces;
  stats.lanelets_oriented_by_neighbours = plan.lanelets_oriented_by_neighbours;
  if (stats_out) *stats_out = stats;
  return osm.xml();
}

void writeOsm(const std::filesystem::path& path, const VectorMap& map,
              const std::vector<DrivePath>& drives, Lanelet2ExportStats* stats) {
  writeBytesAtomic(path, vectorMapToOsm(map, drives, stats));
}

}  // namespace mapfuse::io
