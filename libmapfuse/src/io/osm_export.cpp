#include "mapfuse/io/osm_export.hpp"

#include <algorithm>
#include <map>
#include <optional>

#include "mapfuse/io/atomic_file.hpp"
#include "osm_builder.hpp"

namespace mapfuse::io {
namespace {

using namespace detail;  // the document builder (osm_builder.hpp)
using lanelet::LaneletExportPlan;
using lanelet::LaneletPlan;

constexpr double kLightWidth = 0.3;  // m, the light's line string across the approach

Tags laneLineTags(const MapInstance& m) {
  Tags t = {{"type", "line_thin"},
            {"subtype", m.attributes.style == LineStyle::kDashed ? "dashed" : "solid"}};
  if (m.attributes.color != LineColor::kNone)
    t.push_back({"color", lineColorName(m.attributes.color)});
  return t;
}

/// The export being written: the builder and the ids of what was written so far.
struct Export {
  Export(const VectorMap& m, const LaneletExportPlan& p)
      : map(m),
        plan(p),
        lanes(p.lanes),
        osm(m.origin),
        piece_way(lanes.pieces.size(), 0),
        piece_nodes(lanes.pieces.size()),
        stop_lights(p.stop_lines.size()),
        stop_signs(p.stop_lines.size()),
        lanelet_regs(lanes.lanelets.size()) {}
  const VectorMap& map;
  const LaneletExportPlan& plan;
  const LaneletPlan& lanes;
  OsmBuilder osm;
  Lanelet2ExportStats stats;
  std::vector<int64_t> piece_way;
  std::vector<std::pair<int64_t, int64_t>> piece_nodes;  // first, last
  std::map<std::size_t, int64_t> stop_way;               // instance -> way
  std::vector<std::vector<int64_t>> stop_lights, stop_signs;
  std::vector<std::vector<int64_t>> lanelet_regs;
  std::vector<int64_t> lanelet_id, rule_id;
  OsmSidecar sidecar;  // what Lanelet2's tags cannot say (io/osm_sidecar.hpp)

  /// Notes in the sidecar that OSM element `id` comes from map instance m; returns id.
  int64_t link(const char* element, int64_t id, const MapInstance& m,
               std::optional<double> height = std::nullopt) {
    sidecar.entries.push_back({element, id, m.id, height, 0});
    return id;
  }
};

/// Lane lines: the planned ones piece by piece (shared cut nodes), the others whole.
void writeLaneLines(Export& e) {
  const LaneletPlan& plan = e.lanes;
  std::map<std::size_t, std::size_t> plan_line_of;  // instance -> plan line
  for (std::size_t l = 0; l < plan.lines.size(); ++l) plan_line_of[plan.lines[l].instance] = l;
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> piece_of;  // (line, cut) -> piece
  for (std::size_t k = 0; k < plan.pieces.size(); ++k)
    piece_of[{plan.pieces[k].line, plan.pieces[k].cut}] = k;
  std::vector<bool> is_bound(plan.pieces.size(), false);
  for (const auto& ll : plan.lanelets) is_bound[ll.left] = is_bound[ll.right] = true;
  for (std::size_t i = 0; i < e.map.instances.size(); ++i) {
    const MapInstance& m = e.map.instances[i];
    if (m.cls != CrowdClass::kLaneLine) continue;
    e.stats.lane_line_m += polylineLength(m.points);
    const auto pl = plan_line_of.find(i);
    if (pl == plan_line_of.end()) {
      e.link("way", e.osm.way(m.points, laneLineTags(m)), m);
      continue;
    }
    const auto& line = plan.lines[pl->second];
    std::vector<int64_t> nodes;
    for (const auto& p : line.points) nodes.push_back(e.osm.sharedNode(p));
    for (std::size_t c = 0; c + 1 < line.cuts.size(); ++c) {
      const int64_t w =
          e.osm.way(std::vector<int64_t>(nodes.begin() + static_cast<long>(line.cuts[c]),
                                         nodes.begin() + static_cast<long>(line.cuts[c + 1]) + 1),
                    laneLineTags(m));
      e.link("way", w, m);
      const auto pc = piece_of.find({pl->second, c});
      if (pc == piece_of.end()) continue;
      e.piece_way[pc->second] = w;
      e.piece_nodes[pc->second] = {nodes[line.cuts[c]], nodes[line.cuts[c + 1]]};
      if (is_bound[pc->second])
        e.stats.bound_m += polylineLength(lanelet::piecePoints(plan, pc->second));
    }
  }
}

/// Stop lines, arrows, poles, crosswalks.
void writeMarkings(Export& e) {
  for (std::size_t i = 0; i < e.map.instances.size(); ++i) {
    const MapInstance& m = e.map.instances[i];
    switch (m.cls) {
      case CrowdClass::kStopLine:
        e.stop_way[i] = e.link("way", e.osm.way(m.points, {{"type", "stop_line"}}), m);
        break;
      case CrowdClass::kGroundArrow:
        e.link("way", e.osm.way(m.points, {{"type", "arrow"}}, true), m);
        break;
      case CrowdClass::kPole:
        e.link("node", e.osm.node(m.points.front(), {{"type", "pole"}}), m, m.height);
        break;
      case CrowdClass::kCrosswalk: {
        const auto [left, right] = lanelet::crosswalkBounds(m.points);
        const int64_t l = e.link("way", e.osm.way(left, {{"type", "zebra_marking"}}), m);
        const int64_t r = e.link("way", e.osm.way(right, {{"type", "zebra_marking"}}), m);
        e.link("relation",
               e.osm.relation({{"way", l, "left"}, {"way", r, "right"}}, {{"type", "lanelet"},
                                                                          {"subtype", "crosswalk"},
                                                                          {"location", "urban"},
                                                                          {"one_way", "no"}}),
               m);
        ++e.stats.crosswalk_lanelets;
        break;
      }
      default: break;
    }
  }
}

/// A light: a kLightWidth line string across its approach at the housing's bottom.
int64_t writeLight(Export& e, const MapInstance& m, const Eigen::Vector2d& across) {
  const V3 c = m.points.front();
  const V3 half = 0.5 * kLightWidth * V3(across.x(), across.y(), 0.0);
  return e.link(
      "way",
      e.osm.way({c - half, c + half}, {{"type", "traffic_light"}, {"height", fixed(m.height, 3)}}),
      m);
}

/// A sign: the plate's bottom edge (its two lowest corners), with the plate's height.
int64_t writeSign(Export& e, const MapInstance& m) {
  const std::vector<V3>& corners = m.points;
  std::vector<std::size_t> order(corners.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return corners[a].z() < corners[b].z(); });
  const std::size_t a = std::min(order[0], order[1]), b = std::max(order[0], order[1]);
  double top = corners.front().z();
  for (const auto& q : corners) top = std::max(top, q.z());
  const double height = top - 0.5 * (corners[a].z() + corners[b].z());
  // Lanelet2 refuses a traffic_sign regulatory element whose sign has no subtype (the sign's
  // code, "de205"): the crowd map does not classify signs, so "unknown"
  return e.link(
      "way",
      e.osm.way({corners[a], corners[b]},
                {{"type", "traffic_sign"}, {"subtype", "unknown"}, {"height", fixed(height, 3)}}),
      m);
}

/// Lights and signs, in map order; one without a stop line gets its own regulatory element
/// (referred to by its nearest lanelet, if any); then one element per stop line and kind.
void writeDevices(Export& e) {
  for (const auto& d : e.plan.devices) {
    const MapInstance& m = e.map.instances[d.instance];
    const bool light = m.cls == CrowdClass::kTrafficLight;
    const int64_t w = light ? writeLight(e, m, d.across) : writeSign(e, m);
    if (d.stop >= 0) {
      const auto s = static_cast<std::size_t>(d.stop);
      (light ? e.stop_lights : e.stop_signs)[s].push_back(w);
      continue;
    }
    const int64_t r = e.osm.relation(
        {{"way", w, "refers"}},
        {{"type", "regulatory_element"}, {"subtype", light ? "traffic_light" : "traffic_sign"}});
    ++e.stats.regulatory_elements;
    if (d.lanelet >= 0) e.lanelet_regs[static_cast<std::size_t>(d.lanelet)].push_back(r);
  }
  for (std::size_t s = 0; s < e.plan.stop_lines.size(); ++s) {
    const auto& st = e.plan.stop_lines[s];
    const int64_t line = e.stop_way.at(st.instance);
    for (const auto& [refs, subtype] : {std::make_pair(&e.stop_lights[s], "traffic_light"),
                                        std::make_pair(&e.stop_signs[s], "traffic_sign")}) {
      if (refs->empty()) continue;
      std::vector<Member> members;
      for (int64_t w : *refs) members.push_back({"way", w, "refers"});
      members.push_back({"way", line, "ref_line"});
      const int64_t r =
          e.osm.relation(members, {{"type", "regulatory_element"}, {"subtype", subtype}});
      ++e.stats.regulatory_elements;
      for (std::size_t l : st.lanelets) e.lanelet_regs[l].push_back(r);
    }
  }
}

/// Road lanelets. They and the right-of-way elements refer to each other, so both ids are
/// reserved first: lanelets, then the elements, written in that order (osmium expects
/// relations in id order).
void writeLanelets(Export& e) {
  e.lanelet_id.resize(e.lanes.lanelets.size());
  for (auto& id : e.lanelet_id) id = e.osm.reserve();
  e.rule_id.resize(e.plan.rules.size());
  for (std::size_t k = 0; k < e.plan.rules.size(); ++k) {
    e.rule_id[k] = e.osm.reserve();
    for (const auto* group : {&e.plan.rules[k].yield, &e.plan.rules[k].right_of_way})
      for (std::size_t l : *group) e.lanelet_regs[l].push_back(e.rule_id[k]);
  }
  for (std::size_t l = 0; l < e.lanes.lanelets.size(); ++l) {
    const auto& ll = e.lanes.lanelets[l];
    std::vector<Member> members = {{"way", e.piece_way[ll.left], "left"},
                                   {"way", e.piece_way[ll.right], "right"}};
    for (int64_t r : e.lanelet_regs[l]) members.push_back({"relation", r, "regulatory_element"});
    e.osm.relation(members,
                   {{"type", "lanelet"},
                    {"subtype", "road"},
                    {"location", "urban"},
                    {"one_way", ll.direction_known ? "yes" : "no"}},
                   e.lanelet_id[l]);
    ++e.stats.lanelets;
    e.stats.lanelets_direction_known += ll.direction_known;
    e.stats.lanelets_with_regulatory += !e.lanelet_regs[l].empty();
  }
}

/// Right of way at intersections with stop lines (lanelet/right_of_way.hpp).
void writeRightOfWay(Export& e) {
  for (std::size_t k = 0; k < e.plan.rules.size(); ++k) {
    const lanelet::RightOfWayRule& rule = e.plan.rules[k];
    std::vector<Member> members;
    for (std::size_t l : rule.yield) members.push_back({"relation", e.lanelet_id[l], "yield"});
    for (std::size_t l : rule.right_of_way)
      members.push_back({"relation", e.lanelet_id[l], "right_of_way"});
    if (rule.all_way_stop)  // the signs at the stop lines constitute the rule
      for (std::size_t s : rule.yield_stop)
        for (int64_t w : e.stop_signs[s]) members.push_back({"way", w, "refers"});
    for (std::size_t s : rule.yield_stop)  // in the order of the yield lanelets
      members.push_back({"way", e.stop_way.at(e.plan.stop_lines[s].instance), "ref_line"});
    e.osm.relation(members,
                   {{"type", "regulatory_element"},
                    {"subtype", rule.all_way_stop ? "all_way_stop" : "right_of_way"}},
                   e.rule_id[k]);
    ++(rule.all_way_stop ? e.stats.all_way_stop_elements : e.stats.right_of_way_elements);
  }
}

/// Connectors across intersections: `virtual` bounds sharing the end nodes of the lanelets they
/// join, so that Lanelet2's routing finds the way through.
void writeConnectors(Export& e) {
  for (const auto& c : e.lanes.connectors) {
    std::vector<Member> members;
    for (const bool left : {true, false}) {
      const auto [pa, a_last] = lanelet::boundEnd(e.lanes, e.lanes.lanelets[c.from], left, true);
      const auto [pb, b_last] = lanelet::boundEnd(e.lanes, e.lanes.lanelets[c.to], left, false);
      const auto& pts = left ? c.left : c.right;
      std::vector<int64_t> nodes = {a_last ? e.piece_nodes[pa].second : e.piece_nodes[pa].first};
      for (std::size_t k = 1; k + 1 < pts.size(); ++k) nodes.push_back(e.osm.sharedNode(pts[k]));
      nodes.push_back(b_last ? e.piece_nodes[pb].second : e.piece_nodes[pb].first);
      members.push_back({"way", e.osm.way(nodes, {{"type", "virtual"}}), left ? "left" : "right"});
    }
    const int64_t id = e.osm.relation(
        members,
        {{"type", "lanelet"}, {"subtype", "road"}, {"location", "urban"}, {"one_way", "yes"}});
    e.sidecar.entries.push_back({"relation", id, std::nullopt, std::nullopt, c.drives});
    ++e.stats.connector_lanelets;
  }
}

}  // namespace

std::string vectorMapToOsm(const VectorMap& map, const LaneletExportPlan& plan,
                           Lanelet2ExportStats* stats_out, OsmSidecar* sidecar) {
  Export e(map, plan);
  writeLaneLines(e);
  writeMarkings(e);
  writeDevices(e);
  writeLanelets(e);
  writeRightOfWay(e);
  writeConnectors(e);
  e.stats.unmatched_pieces = plan.lanes.unmatched_pieces;
  e.stats.same_side_lanelets_dropped = plan.lanes.same_side_lanelets_dropped;
  e.stats.lanelets_oriented_by_neighbours = plan.lanes.lanelets_oriented_by_neighbours;
  e.stats.kink_vertices_removed = plan.lanes.kink_vertices_removed;
  e.stats.line_ends_joined = plan.lanes.line_ends_joined;
  e.stats.one_sided_connections = plan.lanes.one_sided_connections;
  e.stats.kink_max_deviation = plan.lanes.kink_max_deviation;
  if (stats_out) *stats_out = e.stats;
  std::string xml = e.osm.xml();
  e.sidecar.osm_hash = fnv1a64Hex(xml);
  if (sidecar) *sidecar = std::move(e.sidecar);
  return xml;
}

void writeOsm(const std::filesystem::path& path, const VectorMap& map,
              const LaneletExportPlan& plan, Lanelet2ExportStats* stats) {
  OsmSidecar sidecar;
  writeBytesAtomic(path, vectorMapToOsm(map, plan, stats, &sidecar));
  writeBytesAtomic(osmSidecarPath(path), osmSidecarToJson(sidecar));
}

}  // namespace mapfuse::io
