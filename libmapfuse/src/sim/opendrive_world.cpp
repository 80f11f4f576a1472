#include "mapfuse/sim/opendrive_world.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <map>
#include <tuple>

#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/io/bounds.hpp"
#include "opendrive_checks.hpp"
#include "opendrive_internal.hpp"

namespace mapfuse::sim {

namespace detail {

OdrContext::OdrContext(const io::OdrMap& m, const geo::GeoOrigin& origin,
                       const OpenDriveAssumptions& a)
    : map(m), assumptions(a), enu(origin) {
  for (const auto& r : map.roads) roads.push_back(std::make_unique<RoadGeometry>(r));
  if (!map.geo_reference.empty())
    projection = geo::MapProjection::fromProj(map.geo_reference, map.file);
}

Eigen::Vector3d OdrContext::toEnu(const Eigen::Vector3d& p) const {
  // OpenDRIVE 1.6 header <offset>: rotate by hdg, then shift, into the projected frame.
  const double c = std::cos(map.offset_hdg), s = std::sin(map.offset_hdg);
  const Eigen::Vector3d q(c * p.x() - s * p.y() + map.offset_x,
                          s * p.x() + c * p.y() + map.offset_y, p.z() + map.offset_z);
  // Every record is bounded when read, but widths, offsets and elevations are polynomials: the
  // point they give is checked (docs/formats.md "Value bounds").
  if (!(q.cwiseAbs().maxCoeff() <= io::bounds::kMaxCoordinate))
    throw InputError(map.file + ": a lane border, signal or object lies at map (" +
                     io::bounds::numberText(q.x()) + ", " + io::bounds::numberText(q.y()) + ", " +
                     io::bounds::numberText(q.z()) + "), beyond " +
                     io::bounds::numberText(io::bounds::kMaxCoordinate) +
                     " m: lane widths, lane offsets or elevation out of range");
  if (!projection) return q;
  return enu.toEnu(projection->toWgs84(q.x(), q.y(), q.z()));
}

std::vector<double> OdrContext::samples(double s0, double s1) const {
  const int n = std::max(1, static_cast<int>(std::ceil((s1 - s0) / assumptions.sample_step)));
  std::vector<double> s;
  for (int k = 0; k <= n; ++k) s.push_back(s0 + (s1 - s0) * k / n);
  return s;
}

}  // namespace detail

namespace {

constexpr double kLinkTolerance = 1.0;  // m between a lane's end and its successor's start
constexpr double kMinLaneWidth = 1.0;   // m; narrower lanes (tapers) are not driven

bool isDrivingLane(const std::string& type) {
  return type == "driving" || type == "entry" || type == "exit" || type == "onRamp" ||
         type == "offRamp" || type == "connectingRamp" || type == "bidirectional";
}

/// A lane of the world and where it came from.
struct LaneRef {
  std::size_t road, section;
  int id;
  bool along_s;  ///< drives with increasing s
};
using LaneKeys = std::map<std::tuple<std::size_t, std::size_t, int>, std::vector<std::size_t>>;

}  // namespace

geo::GeoOrigin openDriveOrigin(const io::OdrMap& map, const geo::GeoOrigin& fallback) {
  if (map.geo_reference.empty()) return fallback;
  const geo::MapProjection proj = geo::MapProjection::fromProj(map.geo_reference, map.file);
  geo::LatLonAlt g = proj.toWgs84(map.offset_x, map.offset_y, 0.0);
  g.alt = fallback.alt;
  return g;
}

namespace {

/// Lanes: every driving lane of every section, in its driving direction (refs parallel to
/// world.lanes; by_key: the world lanes of (road, section, lane id)).
void addLanes(const detail::OdrContext& ctx, World& world, std::vector<LaneRef>& refs,
              LaneKeys& by_key) {
  const io::OdrMap& map = ctx.map;
  for (std::size_t r = 0; r < map.roads.size(); ++r) {
    const io::OdrRoad& road = map.roads[r];
    const RoadGeometry& geo = *ctx.roads[r];
    for (std::size_t k = 0; k < road.sections.size(); ++k) {
      const double s0 = geo.sectionStart(k), s1 = geo.sectionEnd(k);
      if (s1 - s0 < 1e-3) continue;
      for (const io::OdrLane& lane : road.sections[k].lanes) {
        if (lane.id == 0 || !isDrivingLane(lane.type)) continue;
        const int inner = lane.id > 0 ? lane.id - 1 : lane.id + 1;
        Polyline centre;
        double width_sum = 0.0, width_max = 0.0;
        const auto ss = ctx.samples(s0, s1);
        for (double s : ss) {
          const double t = 0.5 * (geo.borderT(k, inner, s) + geo.borderT(k, lane.id, s));
          centre.push_back(ctx.toEnu(geo.point(s, t)));
          const double w = geo.laneWidth(k, lane.id, s);
          width_sum += w;
          width_max = std::max(width_max, w);
        }
        if (width_max < kMinLaneWidth) continue;
        const bool right = lane.id < 0;
        const bool along = road.rule == "LHT" ? !right : right;
        for (bool dir : {along, !along}) {
          if (dir != along && lane.type != "bidirectional") continue;
          Lane l;
          l.id = static_cast<int64_t>(world.lanes.size()) + 1;
          l.centerline = dir ? centre : reversed(centre);
          l.width = width_sum / ss.size();
          by_key[{r, k, lane.id}].push_back(world.lanes.size());
          refs.push_back({r, k, lane.id, dir});
          world.lanes.push_back(std::move(l));
        }
      }
    }
  }
}

using Target = std::tuple<std::size_t, std::size_t, std::optional<int>>;  // road, section, lane

/// Where lane `ref` continues: the next section, the linked road, or the junction's connections.
std::vector<Target> linkTargets(const io::OdrMap& map, const LaneRef& ref,
                                const std::map<std::string, std::size_t>& road_index) {
  const io::OdrRoad& road = map.roads[ref.road];
  const io::OdrLane* lane = road.sections[ref.section].lane(ref.id);
  const std::optional<int> link = ref.along_s ? lane->successor : lane->predecessor;
  auto lastSection = [&](std::size_t r) { return map.roads[r].sections.size() - 1; };
  std::vector<Target> targets;
  const bool inside = ref.along_s ? ref.section + 1 < road.sections.size() : ref.section > 0;
  if (inside) {
    targets.push_back({ref.road, ref.along_s ? ref.section + 1 : ref.section - 1, link});
  } else if (const auto& rl = ref.along_s ? road.successor : road.predecessor; rl) {
    if (rl->element_type == "road" && road_index.count(rl->element_id)) {
      const std::size_t r2 = road_index.at(rl->element_id);
      targets.push_back({r2, rl->contact_point == "end" ? lastSection(r2) : 0, link});
    } else if (rl->element_type == "junction") {
      if (const io::OdrJunction* j = map.junction(rl->element_id))
        for (const auto& c : j->connections) {
          if (c.incoming_road != road.id || !road_index.count(c.connecting_road)) continue;
          const std::size_t r2 = road_index.at(c.connecting_road);
          for (const auto& ll : c.lane_links)
            if (ll.from == ref.id)
              targets.push_back({r2, c.contact_point == "end" ? lastSection(r2) : 0, ll.to});
        }
    }
  }
  return targets;
}

/// Successors from lane links, road links and junction connections: each target lane must start
/// where this one ends (the lane link names it; without a link id the nearest start in the
/// target section). @return {links made, links rejected}.
std::pair<int, int> linkLanes(const io::OdrMap& map, World& world, const std::vector<LaneRef>& refs,
                              const LaneKeys& by_key) {
  std::map<std::string, std::size_t> road_index;
  for (std::size_t r = 0; r < map.roads.size(); ++r) road_index[map.roads[r].id] = r;
  int topological = 0, rejected = 0;
  for (std::size_t i = 0; i < world.lanes.size(); ++i) {
    auto& succ = world.lanes[i].successors;
    const Eigen::Vector3d end = world.lanes[i].centerline.back();
    for (const auto& [r2, k2, id2] : linkTargets(map, refs[i], road_index)) {
      long best = -1;
      double best_d = kLinkTolerance;
      for (auto it = by_key.lower_bound({r2, k2, INT_MIN});
           it != by_key.end() && std::get<0>(it->first) == r2 && std::get<1>(it->first) == k2;
           ++it) {
        if (id2 && std::get<2>(it->first) != *id2) continue;
        for (std::size_t j : it->second) {
          const double d = (world.lanes[j].centerline.front() - end).norm();
          if (j != i && d < best_d) best = static_cast<long>(j), best_d = d;
        }
      }
      if (best < 0) {
        ++rejected;
        continue;
      }
      if (std::find(succ.begin(), succ.end(), static_cast<std::size_t>(best)) == succ.end())
        succ.push_back(static_cast<std::size_t>(best)), ++topological;
    }
  }
  return {topological, rejected};
}

}  // namespace

World worldFromOpenDrive(const io::OdrMap& parsed, const geo::GeoOrigin& origin,
                         const OpenDriveAssumptions& assumptions) {
  io::OdrMap map = parsed;
  checkOpenDriveContent(map);
  const detail::OdrContext ctx(map, origin, assumptions);
  World world;
  world.warnings = map.warnings;
  if (!ctx.projection)
    world.warnings.add("no georeference: map x/y taken as ENU metres about the configured origin",
                       map.file + ": origin " + io::bounds::numberText(origin.lat) + ", " +
                           io::bounds::numberText(origin.lon));
  world.stats["georeferenced"] = ctx.projection ? 1 : 0;
  world.name = map.file;
  world.truth.origin = origin;
  world.truth.source = "simulate ground truth (OpenDRIVE " + map.file + ")";
  std::vector<LaneRef> refs;
  LaneKeys by_key;
  addLanes(ctx, world, refs, by_key);
  const auto [topological, rejected] = linkLanes(map, world, refs, by_key);
  int with_successor = 0;
  for (const auto& l : world.lanes) with_successor += !l.successors.empty();

  detail::addOpenDriveElements(ctx, world);
  world.stats["roads"] = static_cast<double>(map.roads.size());
  world.stats["junctions"] = static_cast<double>(map.junctions.size());
  world.stats["lanes"] = static_cast<double>(world.lanes.size());
  world.stats["lanes_with_successor"] = with_successor;
  world.stats["lane_links"] = topological;
  world.stats["lane_links_rejected"] = rejected;
  return world;
}

}  // namespace mapfuse::sim
