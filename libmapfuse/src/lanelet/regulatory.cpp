#include "mapfuse/lanelet/regulatory.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mapfuse::lanelet {
namespace {

using V3 = Eigen::Vector3d;

constexpr double kStopSample = 0.5;   // m between stop-line samples tested against lanelets
constexpr double kLightBehind = 5.0;  // m a light may stand before its stop line (over the road)
constexpr double kSignBehind = 15.0;  // m a sign may stand before its stop line (at the kerb)

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

/// A stop line with the lanelets it crosses (a sample every kStopSample inside their outline)
/// and the mean travel direction of the oriented ones there.
StopLineLink linkStopLine(const LaneletPlan& plan, const std::vector<Eigen::AlignedBox2d>& boxes,
                          const VectorMap& map, std::size_t i) {
  const auto& pts = map.instances[i].points;
  StopLineLink st{i, 0.5 * (pts.front() + pts.back()), {}, Eigen::Vector2d::Zero()};
  std::vector<V3> samples;
  for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
    const int n =
        std::max(1, static_cast<int>(std::ceil((pts[k + 1] - pts[k]).norm() / kStopSample)));
    for (int q = 0; q <= n; ++q) samples.push_back(pts[k] + (pts[k + 1] - pts[k]) * q / n);
  }
  for (std::size_t l = 0; l < plan.lanelets.size(); ++l) {
    const auto& ll = plan.lanelets[l];
    for (const auto& s : samples)
      if (boxes[l].contains(s.head<2>()) && insideRingXY(ll.ring, s)) {
        st.lanelets.push_back(l);
        if (ll.direction_known) st.approach += directionNear(ll, s);
        break;
      }
  }
  if (st.approach.norm() > 1e-9) st.approach.normalize();
  return st;
}

/// The nearest stop line crossing a lanelet within reach of p that p does not stand more than
/// `behind` before (along its approach); -1 when none.
long nearestStop(const std::vector<StopLineLink>& stops, const V3& p, double behind, double reach) {
  long best = -1;
  double best_d = reach;
  for (std::size_t s = 0; s < stops.size(); ++s) {
    const auto& st = stops[s];
    const double d = (p - st.mid).head<2>().norm();
    if (d > best_d || st.lanelets.empty()) continue;
    if (st.approach.norm() > 0 && st.approach.dot((p - st.mid).head<2>()) < -behind) continue;
    best = static_cast<long>(s);
    best_d = d;
  }
  return best;
}

long nearestLanelet(const LaneletPlan& plan, const V3& p, double reach) {
  long best = -1;
  double best_d = reach;
  for (std::size_t l = 0; l < plan.lanelets.size(); ++l) {
    const double d = distanceToCentre(plan.lanelets[l], p);
    if (d < best_d) best = static_cast<long>(l), best_d = d;
  }
  return best;
}

/// The middle of a sign plate's bottom edge (its two lowest corners).
V3 signBottom(const std::vector<V3>& corners) {
  std::vector<std::size_t> order(corners.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return corners[a].z() < corners[b].z(); });
  const std::size_t a = std::min(order[0], order[1]), b = std::max(order[0], order[1]);
  return 0.5 * (corners[a] + corners[b]);
}

/// Lights and signs: each tied to the nearest stop line it serves, else to the nearest lanelet.
std::vector<DeviceLink> linkDevices(const LaneletExportPlan& out, const VectorMap& map,
                                    const LaneletSettings& settings) {
  std::vector<DeviceLink> devices;
  for (std::size_t i = 0; i < map.instances.size(); ++i) {
    const MapInstance& m = map.instances[i];
    const bool light = m.cls == CrowdClass::kTrafficLight;
    if (!light && m.cls != CrowdClass::kTrafficSign) continue;
    const V3 c = light ? m.points.front() : signBottom(m.points);
    DeviceLink d;
    d.instance = i;
    d.stop = nearestStop(out.stop_lines, c, light ? kLightBehind : kSignBehind,
                         settings.regulatory_reach);
    if (d.stop < 0 || light) d.lanelet = nearestLanelet(out.lanes, c, settings.lone_reach);
    if (light) {
      const auto& st = d.stop >= 0 ? &out.stop_lines[static_cast<std::size_t>(d.stop)] : nullptr;
      if (st && st->approach.norm() > 0) {
        d.across = {-st->approach.y(), st->approach.x()};
      } else if (d.lanelet >= 0) {
        const Eigen::Vector2d dir =
            directionNear(out.lanes.lanelets[static_cast<std::size_t>(d.lanelet)], c);
        d.across = {-dir.y(), dir.x()};
      }
    }
    if (d.stop >= 0) d.lanelet = -1;
    devices.push_back(d);
  }
  return devices;
}

}  // namespace

LaneletExportPlan planExport(const VectorMap& map, const std::vector<DrivePath>& drives,
                             const LaneletSettings& settings) {
  LaneletExportPlan out;
  out.lanes = planLanelets(map, drives, settings);
  const std::vector<Eigen::AlignedBox2d> boxes = laneletBoxes(out.lanes);
  for (std::size_t i = 0; i < map.instances.size(); ++i)
    if (map.instances[i].cls == CrowdClass::kStopLine)
      out.stop_lines.push_back(linkStopLine(out.lanes, boxes, map, i));
  out.devices = linkDevices(out, map, settings);
  // A stop line is signalled when a light stands within reach of it, whether or not the light
  // was tied to it (that needs a lanelet across the stop line).
  std::vector<RightOfWayStop> stops;
  for (std::size_t s = 0; s < out.stop_lines.size(); ++s) {
    bool lit = false;
    for (const auto& d : out.devices)
      lit |= d.stop == static_cast<long>(s) &&
             map.instances[d.instance].cls == CrowdClass::kTrafficLight;
    for (const MapInstance& m : map.instances)
      lit |=
          m.cls == CrowdClass::kTrafficLight &&
          (m.points.front() - out.stop_lines[s].mid).head<2>().norm() <= settings.regulatory_reach;
    stops.push_back({map.instances[out.stop_lines[s].instance].points, lit});
  }
  out.rules = deriveRightOfWay(out.lanes, stops, drives, settings);
  return out;
}

}  // namespace mapfuse::lanelet
