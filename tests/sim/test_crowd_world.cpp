// The procedural world's content (issue 3: "multi-lane roads with curves, a bifurcation and a
// merge, intersections with stop lines, ground arrows, signs and poles"), checked on the lane
// graph and the true elements the world exposes, with the world `simulate` builds by default.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <set>

#include "mapfuse/sim/drive.hpp"
#include "mapfuse/sim/polyline.hpp"
#include "mapfuse/sim/procedural_world.hpp"
#include "mapfuse/sim/world.hpp"
#include "mapfuse/stages/simulate.hpp"

using namespace mapfuse;

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr uint64_t kWorldSeedIndex = 1000001;  // sim/crowd.cpp: deriveSeed(seed, this)
constexpr double kMidRoad = 30.0;              // m, a fork / merge this far from every stop line
constexpr double kOnElement = 0.1;             // m, a point "on" a line, a pole "under" a sign
constexpr double kSideBySideTolerance = 0.1;   // m, |centre distance - mean width| of neighbours
constexpr double kParallel = 0.985;            // cos(10 deg): neighbouring lanes run parallel
constexpr double kRoadLaneLength = 100.0;      // m, longer than any intersection connector
constexpr double kMinHeadingSwing = 30.0;      // deg, max - min heading along one road lane
constexpr double kArrowBeforeStop = 12.0;      // m, docs/simulate.md
// m, along the lane: arrows are placed 12 m along the road's centre line, and an offset lane on
// the curved road end is up to ~1 m longer or shorter over those 12 m (measured worst 1.0 m).
constexpr double kArrowTolerance = 1.5;
constexpr double kArrowOnLane = 0.3;  // m, arrow centre to its lane's centreline

sim::World defaultWorld(uint64_t seed = stages::SimulateParams{}.crowd.seed) {
  const stages::SimulateParams p;
  geo::GeoOrigin origin;
  origin.lat = p.origin_lat;
  origin.lon = p.origin_lon;
  origin.alt = p.origin_alt;
  return sim::buildProceduralWorld(p.crowd.world, origin, sim::deriveSeed(seed, kWorldSeedIndex));
}

std::vector<const MapInstance*> instancesOf(const sim::World& w, CrowdClass cls) {
  std::vector<const MapInstance*> out;
  for (const auto& m : w.truth.instances)
    if (m.cls == cls) out.push_back(&m);
  return out;
}

double distanceToAny(const std::vector<const MapInstance*>& lines, const Eigen::Vector3d& p) {
  double best = 1e18;
  for (const auto* m : lines) best = std::min(best, sim::distanceToPolyline(m->points, p));
  return best;
}

std::vector<std::vector<std::size_t>> predecessors(const sim::World& w) {
  std::vector<std::vector<std::size_t>> pred(w.lanes.size());
  for (std::size_t i = 0; i < w.lanes.size(); ++i)
    for (std::size_t j : w.lanes[i].successors) pred[j].push_back(i);
  return pred;
}

Eigen::Vector3d directionAt(const sim::Polyline& line, std::size_t i) {
  const std::size_t a = i == 0 ? 0 : i - 1, b = std::min(i + 1, line.size() - 1);
  return (line[b] - line[a]).normalized();
}

std::size_t nearestVertex(const sim::Polyline& line, const Eigen::Vector3d& p) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < line.size(); ++i)
    if ((line[i] - p).squaredNorm() < (line[best] - p).squaredNorm()) best = i;
  return best;
}

/// Arc length of the point of `line` nearest to p (projection onto its nearest segment), m.
double arcOfProjection(const sim::Polyline& line, const Eigen::Vector3d& p) {
  const auto cum = sim::arcLengths(line);
  double best = 1e18, arc = 0.0;
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    const Eigen::Vector3d d = line[i + 1] - line[i];
    const double t = std::clamp((p - line[i]).dot(d) / d.squaredNorm(), 0.0, 1.0);
    const double e = (line[i] + t * d - p).norm();
    if (e < best) best = e, arc = cum[i] + t * (cum[i + 1] - cum[i]);
  }
  return arc;
}

/// Max minus min of the unwrapped heading along a line, degrees.
double headingSwingDeg(const sim::Polyline& line) {
  double h = 0.0, lo = 0.0, hi = 0.0, prev = 0.0;
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    const Eigen::Vector3d d = line[i + 1] - line[i];
    const double a = std::atan2(d.y(), d.x());
    if (i > 0) h += std::remainder(a - prev, 2.0 * kPi);
    prev = a;
    lo = std::min(lo, h);
    hi = std::max(hi, h);
  }
  return (hi - lo) * 180.0 / kPi;
}
}  // namespace

TEST_CASE("simulate world: a fork and a merge away from intersections in the lane graph",
          "[sim][world]") {
  for (uint64_t seed : {uint64_t{42}, uint64_t{1}, uint64_t{7}, uint64_t{2024}, uint64_t{99}}) {
    const sim::World w = defaultWorld(seed);
    const auto stops = instancesOf(w, CrowdClass::kStopLine);
    const auto pred = predecessors(w);
    std::vector<std::size_t> forks, merges;
    for (std::size_t i = 0; i < w.lanes.size(); ++i) {
      const auto& c = w.lanes[i].centerline;
      if (w.lanes[i].successors.size() >= 2 && distanceToAny(stops, c.back()) > kMidRoad)
        forks.push_back(i);
      if (pred[i].size() >= 2 && distanceToAny(stops, c.front()) > kMidRoad) merges.push_back(i);
    }
    INFO("seed " << seed << ": " << forks.size() << " forks, " << merges.size() << " merges");
    REQUIRE(forks.size() == 1);
    REQUIRE(merges.size() == 1);
    // Both branches of the fork lead into the merge: a bypass, not two dead ends.
    const auto& branches = w.lanes[forks[0]].successors;
    CHECK(branches.size() == 2);
    for (std::size_t b : branches) {
      const auto& next = w.lanes[b].successors;
      CHECK(std::find(next.begin(), next.end(), merges[0]) != next.end());
    }
    // The branches separate: their mid points lie apart by more than a lane width.
    const auto mid = [&](std::size_t i) {
      const auto& c = w.lanes[i].centerline;
      return c[c.size() / 2];
    };
    CHECK((mid(branches[0]) - mid(branches[1])).norm() > w.lanes[branches[0]].width);
  }
}

TEST_CASE("simulate world: the default world's roads, markings, signs and poles", "[sim][world]") {
  const sim::World w = defaultWorld();
  const auto stops = instancesOf(w, CrowdClass::kStopLine);
  const auto arrows = instancesOf(w, CrowdClass::kGroundArrow);
  const auto signs = instancesOf(w, CrowdClass::kTrafficSign);
  const auto lights = instancesOf(w, CrowdClass::kTrafficLight);
  const auto poles = instancesOf(w, CrowdClass::kPole);
  const auto lines = instancesOf(w, CrowdClass::kLaneLine);

  SECTION("multi-lane: two same-direction lanes side by side with a dashed line between") {
    std::vector<const MapInstance*> dashed;
    for (const auto* m : lines)
      if (m->attributes.style == LineStyle::kDashed) dashed.push_back(m);
    int pairs = 0;
    for (std::size_t i = 0; i < w.lanes.size(); ++i)
      for (std::size_t j = i + 1; j < w.lanes.size(); ++j) {
        const auto &a = w.lanes[i], &b = w.lanes[j];
        if (polylineLength(a.centerline) < kRoadLaneLength) continue;
        const std::size_t ia = a.centerline.size() / 2;
        const Eigen::Vector3d p = a.centerline[ia];
        const std::size_t ib = nearestVertex(b.centerline, p);
        const double gap = sim::distanceToPolyline(b.centerline, p);
        if (std::abs(gap - 0.5 * (a.width + b.width)) > kSideBySideTolerance) continue;
        if (directionAt(a.centerline, ia).dot(directionAt(b.centerline, ib)) < kParallel) continue;
        // Sharing a bound: the line between them is a dashed divider.
        CHECK(distanceToAny(dashed, 0.5 * (p + b.centerline[ib])) < kOnElement);
        ++pairs;
      }
    INFO(pairs << " pairs of same-direction neighbouring lanes");
    CHECK(pairs >= 1);
  }

  SECTION("curves: some road lane turns by at least kMinHeadingSwing") {
    double swing = 0.0;
    for (const auto& l : w.lanes)
      if (polylineLength(l.centerline) >= kRoadLaneLength)
        swing = std::max(swing, headingSwingDeg(l.centerline));
    INFO("largest heading swing along a road lane " << swing << " deg");
    CHECK(swing >= kMinHeadingSwing);
  }

  SECTION("stop lines at every road end, across lanes that enter an intersection") {
    CHECK(stops.size() == 2 * static_cast<std::size_t>(w.stats.at("roads")));
    for (const auto* s : stops) {
      int entering = 0;
      for (const auto& l : w.lanes)
        if (!l.successors.empty() &&
            sim::distanceToPolyline(s->points, l.centerline.back()) < kOnElement)
          ++entering;
      CHECK(entering >= 1);
    }
  }

  SECTION("ground arrows on the lanes, kArrowBeforeStop before every stop line") {
    REQUIRE(!arrows.empty());
    double worst = 0.0;
    std::set<std::size_t> stops_with_arrows;
    for (const auto* a : arrows) {
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      for (const auto& q : a->points) c += q / static_cast<double>(a->points.size());
      double best = 1e18;  // |distance to the stop line along the lane - kArrowBeforeStop|
      std::size_t best_stop = stops.size();
      for (const auto& l : w.lanes) {
        if (sim::distanceToPolyline(l.centerline, c) > kArrowOnLane) continue;
        for (std::size_t k = 0; k < stops.size(); ++k) {
          if (sim::distanceToPolyline(stops[k]->points, l.centerline.back()) > kOnElement) continue;
          const double ahead = polylineLength(l.centerline) - arcOfProjection(l.centerline, c);
          if (std::abs(ahead - kArrowBeforeStop) < best)
            best = std::abs(ahead - kArrowBeforeStop), best_stop = k;
        }
      }
      worst = std::max(worst, best);
      stops_with_arrows.insert(best_stop);
    }
    INFO(arrows.size() << " arrows, worst |distance to the stop line - " << kArrowBeforeStop
                       << " m| " << worst << " m");
    CHECK(worst < kArrowTolerance);
    CHECK(stops_with_arrows.size() == stops.size());
    CHECK(stops_with_arrows.count(stops.size()) == 0);  // no arrow without a stop line ahead
  }

  SECTION("signs and traffic lights stand on poles") {
    REQUIRE(!signs.empty());
    const auto poleUnder = [&](const Eigen::Vector3d& p, double bottom) {
      for (const auto* q : poles)
        if ((q->points[0] - p).head<2>().norm() < kOnElement && q->height >= bottom) return true;
      return false;
    };
    for (const auto* s : signs) {
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      double bottom = 1e18;
      for (const auto& q : s->points) {
        c += q / static_cast<double>(s->points.size());
        bottom = std::min(bottom, q.z());
      }
      CHECK(poleUnder(c, bottom));
    }
    for (const auto* l : lights) CHECK(poleUnder(l->points[0], l->points[0].z()));
    INFO(signs.size() << " signs, " << lights.size() << " lights, " << poles.size() << " poles");
    CHECK(poles.size() > signs.size() + lights.size());  // street lamps too
  }

  SECTION("lane lines: solid and dashed") {
    int solid = 0, dashed = 0;
    for (const auto* m : lines) {
      solid += m->attributes.style == LineStyle::kSolid;
      dashed += m->attributes.style == LineStyle::kDashed;
    }
    INFO(solid << " solid, " << dashed << " dashed");
    CHECK(solid > 0);
    CHECK(dashed > 0);
  }
}

TEST_CASE("simulate routes: a lane far longer than the route is cut 1 km past the target",
          "[sim][world][bounds]") {
  // Fuzz finding (fuzz_lanelet2_osm): whole lanes were appended until the target length was
  // reached, so one 365 km lanelet made a 365 km route and drives of 28,000 s (2.9 GB).
  constexpr double kTarget = 1500.0, kOvershoot = 1000.0;  // m; drive.cpp's cut
  sim::World world;
  sim::Lane lane;
  lane.centerline = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(50000, 0, 0)};  // one 50 km lane
  world.lanes.push_back(lane);
  const auto routes = sim::planRoutes(world, 3, kTarget, 7);
  REQUIRE(routes.size() == 3);
  for (const auto& route : routes) {
    const double length = sim::arcLengths(route).back();
    CHECK(length == Approx(kTarget + kOvershoot).margin(1e-6));
    CHECK(route.back().x() == Approx(kTarget + kOvershoot).margin(1e-6));
  }
  // A lane shorter than the cut keeps its whole length (routes of street maps are unchanged).
  world.lanes[0].centerline = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2400, 0, 0)};
  CHECK(sim::arcLengths(sim::planRoutes(world, 1, kTarget, 7).front()).back() ==
        Approx(2400.0).margin(1e-6));
}

TEST_CASE("simulate world: a 400 km dashed lane line is cut into its dashes",
          "[sim][world][bounds]") {
  // Triage of fuzz_opendrive_drive's slow inputs (issue 37): every dash of a dashed lane line
  // re-measured the whole line, O(dashes x points). Release build, 2-core machine at load 5:
  // 100 km of dashed line took 20.8 s to cut (0.02 s now), and simulate on a 1 KB .xodr of one
  // 100 km road with a broken centre mark 51 s. Here 400 km, 800,001 points and 44,445
  // dashes: about 3.6e10 steps before (minutes), 0.09 s now in release. No clock here (unit
  // tests are not timed); the fuzz target's timeout and the bench guard the cost.
  constexpr double kLength = 400000.0, kStep = 0.5;
  MapInstance line;
  line.cls = CrowdClass::kLaneLine;
  line.attributes.style = LineStyle::kDashed;
  for (int i = 0; i <= static_cast<int>(kLength / kStep); ++i)
    line.points.emplace_back(i * kStep, 0.0, 0.0);
  const sim::DashPattern dashes;  // 3 m dash, 6 m gap
  const auto pieces = sim::observablePieces(line, dashes, kStep);
  const auto period = dashes.dash + dashes.gap;
  REQUIRE(pieces.size() == static_cast<std::size_t>(std::ceil((kLength - 0.3) / period)));
  for (std::size_t k : {std::size_t{0}, pieces.size() / 2, pieces.size() - 1}) {
    INFO("dash " << k);
    REQUIRE(pieces[k].size() == 7);  // 3 m at 0.5 m
    CHECK(pieces[k].front().x() == Approx(k * period).margin(1e-6));
    CHECK(pieces[k].back().x() == Approx(k * period + dashes.dash).margin(1e-6));
  }
}
