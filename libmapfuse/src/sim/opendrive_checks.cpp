#include "opendrive_checks.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/bounds.hpp"
#include "opendrive_geometry.hpp"

namespace mapfuse::sim {

namespace {

constexpr int kMinCurveSamples = 4, kMaxCurveSamples = 64;  // per plan-view record
constexpr int kWidthSamples = 8;                            // per width record

std::string num(double v) {
  return io::bounds::numberText(v);
}

/// Length of a record as drawn: chords of up to kMaxCurveSamples samples.
double drawnLength(const io::OdrGeometry& g) {
  const int n =
      std::clamp(static_cast<int>(std::ceil(g.length)), kMinCurveSamples, kMaxCurveSamples);
  double len = 0.0;
  RefPose prev = evalGeometry(g, 0.0);
  for (int k = 1; k <= n; ++k) {
    const RefPose p = evalGeometry(g, g.length * k / n);
    len += std::hypot(p.x - prev.x, p.y - prev.y);
    prev = p;
  }
  return len;
}

/// Plan view: zero-length records ignored, collapsed curves refused, gaps checked, the road
/// length made the plan view's. @return false when the road is to be dropped.
bool checkPlanView(io::OdrRoad& road, io::OdrMap& map, const OdrCheckLimits& L) {
  const std::string where = map.file + ": road " + road.id;
  auto& pv = road.plan_view;
  for (const auto& g : pv)
    if (g.length < 1e-9)
      map.warnings.add("plan-view geometry of length 0 (ignored)",
                       where + " geometry s=" + num(g.s));
  pv.erase(std::remove_if(pv.begin(), pv.end(), [](const auto& g) { return g.length < 1e-9; }),
           pv.end());
  if (pv.empty()) {
    map.warnings.add("road without a plan view of positive length (dropped)", where);
    return false;
  }
  for (std::size_t i = 0; i < pv.size(); ++i) {
    const io::OdrGeometry& g = pv[i];
    const double drawn = drawnLength(g);
    if (drawn < L.min_curve_ratio * g.length || drawn > L.max_curve_ratio * g.length + 1.0)
      throw ParseError(map.file, "road " + road.id + " planView geometry s=" + num(g.s),
                       "the curve is " + num(drawn) + " m long as drawn for a stated length of " +
                           num(g.length) + " m (degenerate geometry)");
    if (i == 0) continue;
    const RefPose end = evalGeometry(pv[i - 1], pv[i - 1].length);
    const double gap = std::hypot(g.x - end.x, g.y - end.y);
    if (gap > L.max_gap) {
      map.warnings.add("plan view with a gap > " + num(L.max_gap) + " m (road dropped)",
                       where + " geometry s=" + num(g.s) + ": " + num(gap) + " m gap");
      return false;
    }
    if (gap > L.join)
      map.warnings.add("plan view with a gap <= " + num(L.max_gap) + " m (joined)",
                       where + " geometry s=" + num(g.s) + ": " + num(gap) + " m gap");
  }
  const double end = pv.back().s + pv.back().length;
  if (std::abs(end - road.length) > L.length_slack + 1e-6 * end) {
    map.warnings.add("road length differs from its plan view (plan view's length used)",
                     where + " length=" + num(road.length) + ", plan view ends at s=" + num(end));
    road.length = end;
  }
  return true;
}

/// Lane sections within the road, lane widths within physical bounds.
void checkLanes(io::OdrRoad& road, io::OdrMap& map, const OdrCheckLimits& L) {
  const std::string where = map.file + ": road " + road.id;
  auto& secs = road.sections;
  for (std::size_t k = 1; k < secs.size();)
    if (secs[k].s > road.length - 1e-3) {
      map.warnings.add(
          "lane section beyond its road's end (dropped)",
          where + " laneSection s=" + num(secs[k].s) + ", road length " + num(road.length));
      secs.erase(secs.begin() + static_cast<long>(k));
    } else {
      ++k;
    }
  for (std::size_t k = 0; k < secs.size(); ++k) {
    const double len = (k + 1 < secs.size() ? secs[k + 1].s : road.length) - secs[k].s;
    for (const io::OdrLane& lane : secs[k].lanes)
      for (std::size_t w = 0; w < lane.widths.size(); ++w) {
        const io::OdrPoly3& p = lane.widths[w];
        const double b = w + 1 < lane.widths.size() ? lane.widths[w + 1].s : len;
        for (int i = 0; i <= kWidthSamples && p.s <= b; ++i) {
          const double ds = p.s + (b - p.s) * i / kWidthSamples, v = p.at(ds);
          const std::string field = "road " + road.id + " laneSection s=" + num(secs[k].s) +
                                    " lane " + std::to_string(lane.id) +
                                    " width sOffset=" + num(p.s);
          if (v > L.max_lane_width)
            throw ParseError(map.file, field,
                             "the lane is " + num(v) + " m wide at sOffset " + num(ds) +
                                 ", beyond " + num(L.max_lane_width) + " m");
          if (v < -L.negative_width) {
            map.warnings.add("negative lane width (taken as 0)",
                             map.file + ": " + field + ": " + num(v) + " m");
            break;
          }
        }
      }
  }
}

/// Signals and objects placed beyond their road's end are dropped.
void checkPlacements(io::OdrRoad& road, io::OdrMap& map, const OdrCheckLimits& L) {
  auto beyond = [&](const auto& e) { return e.s > road.length + L.beyond_end; };
  for (const auto& sig : road.signals)
    if (beyond(sig))
      map.warnings.add("signal beyond its road's end (dropped)",
                       map.file + ": road " + road.id + " signal " + sig.id + " s=" + num(sig.s) +
                           ", road length " + num(road.length));
  for (const auto& obj : road.objects)
    if (beyond(obj))
      map.warnings.add("object beyond its road's end (dropped)",
                       map.file + ": road " + road.id + " object " + obj.id + " s=" + num(obj.s) +
                           ", road length " + num(road.length));
  road.signals.erase(std::remove_if(road.signals.begin(), road.signals.end(), beyond),
                     road.signals.end());
  road.objects.erase(std::remove_if(road.objects.begin(), road.objects.end(), beyond),
                     road.objects.end());
}

/// Road links and junction connections naming a road or junction the map lacks are dropped.
void checkLinks(io::OdrMap& map) {
  std::set<std::string> roads, junctions;
  for (const auto& r : map.roads) roads.insert(r.id);
  for (const auto& j : map.junctions) junctions.insert(j.id);
  for (auto& r : map.roads)
    for (auto* link : {&r.predecessor, &r.successor}) {
      if (!*link) continue;
      const auto& l = **link;
      const bool ok = (l.element_type == "road" && roads.count(l.element_id)) ||
                      (l.element_type == "junction" && junctions.count(l.element_id));
      if (ok) continue;
      map.warnings.add(
          "road link to a missing road or junction (dropped)",
          map.file + ": road " + r.id + " links to " + l.element_type + " '" + l.element_id + "'");
      link->reset();
    }
  for (auto& j : map.junctions) {
    auto missing = [&](const io::OdrConnection& c) {
      return !roads.count(c.incoming_road) || !roads.count(c.connecting_road);
    };
    for (const auto& c : j.connections)
      if (missing(c))
        map.warnings.add("junction connection with a missing road (dropped)",
                         map.file + ": junction " + j.id + " connection " + c.id +
                             " (incomingRoad '" + c.incoming_road + "', connectingRoad '" +
                             c.connecting_road + "')");
    j.connections.erase(std::remove_if(j.connections.begin(), j.connections.end(), missing),
                        j.connections.end());
  }
}

}  // namespace

void checkOpenDriveContent(io::OdrMap& map, const OdrCheckLimits& limits) {
  std::vector<io::OdrRoad> kept;
  for (io::OdrRoad& road : map.roads) {
    if (!checkPlanView(road, map, limits)) continue;
    checkLanes(road, map, limits);
    checkPlacements(road, map, limits);
    kept.push_back(std::move(road));
  }
  map.roads = std::move(kept);
  if (map.roads.empty())
    throw InputError(map.file + ": no road is left after the content checks (" +
                     map.warnings.entries().begin()->second.first + ")");
  checkLinks(map);
}

}  // namespace mapfuse::sim
