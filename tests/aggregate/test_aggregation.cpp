#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <map>

#include "aggregate/discrete_merge.hpp"
#include "mapfuse/aggregate/aggregator.hpp"
#include "mapfuse/aggregate/geometry2d.hpp"
#include "mapfuse/core/error.hpp"
#include "support/test_support.hpp"
#include "synthetic_world.hpp"

using namespace mapfuse;
using namespace mapfuse::aggregate;
using Vec3 = Eigen::Vector3d;

namespace {

constexpr double kLanePointTolerance = 0.10;  // m, every map lane point to its truth line
constexpr double kDiscreteTolerance = 0.15;   // m, merged centre to truth centre

using test::distanceToTruth;
using test::observe;
using test::ofClass;

// A synthetic road with lane lines only, and its map aggregated with the default parameters.
struct LaneRun {
  test::SynthWorld world;
  VectorMap map;
  AggregatorStats stats;
};
test::SynthOptions lanesOnly() {
  test::SynthOptions o;
  o.discrete = false;
  return o;
}
LaneRun aggregateLanes(const test::SynthOptions& o) {
  LaneRun r{test::makeSynthWorld(o), {}, {}};
  r.map = aggregateObservations(observe(r.world), AggregatorParams{}, &r.stats);
  return r;
}

Vec3 centre(const MapInstance& m) {
  Vec3 c = Vec3::Zero();
  for (const auto& p : m.points) c += p;
  return c / double(m.points.size());
}

}  // namespace

TEST_CASE("a straight three-line road gives three lane instances on the truth",
          "[aggregate][lanes]") {
  const test::SynthOptions o = lanesOnly();
  const auto [w, map, stats] = aggregateLanes(o);
  const auto lanes = ofClass(map, CrowdClass::kLaneLine);
  REQUIRE(lanes.size() == 3);
  CHECK(stats.lanes.branch_ends == 0);
  double covered = 0;
  for (const auto* l : lanes) {
    CHECK(l->bezier.size() >= 1);
    CHECK(l->support.drives == o.drives);
    covered += polylineLength(l->points);
    for (const auto& p : l->points)
      CHECK(distanceToTruth(p, w.truth, CrowdClass::kLaneLine) < kLanePointTolerance);
    // attributes by majority vote: the middle line is dashed, the y = 7 line yellow
    const double y = l->points.front().y();
    CHECK(l->attributes.style == (std::abs(y - 3.5) < 1 ? LineStyle::kDashed : LineStyle::kSolid));
    CHECK(l->attributes.color == (std::abs(y - 7) < 1 ? LineColor::kYellow : LineColor::kWhite));
  }
  CHECK(covered >= 0.95 * 3 * o.length);
  CHECK(stats.bezier_max_deviation <= AggregatorParams{}.bezier.max_deviation);
}

TEST_CASE("a dashed line observed dash by dash is one instance over its whole length",
          "[aggregate][lanes]") {
  // 3 m dashes, 6 m gaps (the simulator's pattern), 10 m tiles: tile edges cut dashes into
  // stubs, and several dashes lie within the 8 m link distance of every fragment end
  constexpr double kMinCoverage = 0.95;  // of the road length
  // 10 drives offset by 0.15 m each: their mean is within ~0.15 m (3 sigma), plus Bezier error
  constexpr double kDashedLineTolerance = 0.25;  // m
  for (uint64_t seed : {1, 2, 3}) {
    test::SynthOptions o = lanesOnly();
    o.dash_length = 3.0;
    o.dash_gap = 6.0;
    o.drive_sigma = 0.15;
    o.seed = seed;
    const auto [w, map, stats] = aggregateLanes(o);
    const auto lanes = ofClass(map, CrowdClass::kLaneLine);
    CHECK(lanes.size() == 3);
    CHECK(stats.lanes.branch_ends == 0);
    for (const auto* l : lanes) {
      if (std::abs(l->points.front().y() - 3.5) > 1) continue;
      CHECK(l->attributes.style == LineStyle::kDashed);
      CHECK(polylineLength(l->points) >= kMinCoverage * o.length);
      for (const auto& p : l->points)
        CHECK(distanceToTruth(p, w.truth, CrowdClass::kLaneLine) < kDashedLineTolerance);
    }
  }
}

TEST_CASE("a fork splits its line into three instances", "[aggregate][lanes]") {
  test::SynthOptions o = lanesOnly();
  o.fork = true;
  const auto [w, map, stats] = aggregateLanes(o);
  // y = 3.5 and y = 7 lines, plus trunk before the fork, trunk after it and the branch
  CHECK(ofClass(map, CrowdClass::kLaneLine).size() == 5);
  CHECK(stats.lanes.branch_ends >= 1);
  // within one tile of the fork the trunk and the branch (< 0.5 m apart) are averaged together
  constexpr double kForkTileTolerance = 0.4;  // m
  std::size_t total = 0, close = 0;
  for (const auto* l : ofClass(map, CrowdClass::kLaneLine))
    for (const auto& p : l->points) {
      const double d = distanceToTruth(p, w.truth, CrowdClass::kLaneLine);
      CHECK(d < kForkTileTolerance);
      ++total;
      close += d < kLanePointTolerance;
    }
  CHECK(double(close) >= 0.97 * double(total));
}

TEST_CASE("painted lines crossing in a junction keep both lines", "[aggregate][lanes]") {
  // A 30 m line crossing the three road lines at 35, 45, 60 and 90 deg, at three positions
  // against the 10 m tile grid (tile corners cut short pieces that the crossing line's buffer
  // covers). With piece_angle_deg 90 (the test off) the map zig-zags up to 1.5-1.7 m off the
  // lines here.
  constexpr double kCrossingTolerance = 0.15;   // m, every map lane point to its truth line
  constexpr double kMinCrossingCoverage = 0.8;  // of the crossing line's 30 m
  for (double angle : {35.0, 45.0, 60.0, 90.0})
    for (double x : {100.0, 103.3, 106.6}) {
      test::SynthOptions o = lanesOnly();
      o.crossing_deg = angle;
      o.crossing_x = x;
      const auto [w, map, stats] = aggregateLanes(o);
      const MapInstance& crossing = w.truth.instances.back();
      INFO("angle " << angle << " deg at x = " << x);
      double covered = 0.0;
      for (const auto* l : ofClass(map, CrowdClass::kLaneLine)) {
        for (const auto& p : l->points)
          CHECK(distanceToTruth(p, w.truth, CrowdClass::kLaneLine) < kCrossingTolerance);
        // length of the instance lying along the crossing line
        for (std::size_t k = 1; k < l->points.size(); ++k)
          if (distanceToPolyline2d(l->points[k - 1], crossing.points) < kCrossingTolerance &&
              distanceToPolyline2d(l->points[k], crossing.points) < kCrossingTolerance)
            covered += (l->points[k] - l->points[k - 1]).head<2>().norm();
      }
      INFO(covered << " m of 30 covered");
      CHECK(covered >= kMinCrossingCoverage * polylineLength(crossing.points));
    }
}

TEST_CASE("a skewed crosswalk keeps its shape", "[aggregate][discrete]") {
  constexpr double kShapeTol = 0.2;  // m, acceptance: every merged corner to its true corner
  for (const std::string method : {"dbscan_bezier", "grid_vote"}) {
    test::SynthOptions o;
    o.crosswalk_deg = 60.0;
    const test::SynthWorld w = test::makeSynthWorld(o);
    AggregatorParams params;
    params.method = method;
    const VectorMap map = aggregateObservations(observe(w), params);
    const auto truth = ofClass(w.truth, CrowdClass::kCrosswalk);
    const auto found = ofClass(map, CrowdClass::kCrosswalk);
    REQUIRE(truth.size() == 1);
    REQUIRE(found.size() == 1);
    CHECK(found[0]->points.size() == 4);
    // The grid's cells reach half a cell (5 cm) beyond the paint, and its corners are cut.
    for (const auto& c : truth[0]->points) {
      double nearest = 1e300;
      for (const auto& v : found[0]->points) nearest = std::min(nearest, (v - c).head<2>().norm());
      INFO(method << ": true corner (" << c.x() << ", " << c.y() << ") nearest " << nearest
                  << " m");
      CHECK(nearest <= kShapeTol);
    }
  }
}

TEST_CASE("a merge ends both incoming lines and starts a new instance", "[aggregate][lanes]") {
  test::SynthOptions o = lanesOnly();
  o.merge = true;
  const auto [w, map, stats] = aggregateLanes(o);
  CHECK(ofClass(map, CrowdClass::kLaneLine).size() == 5);
  CHECK(stats.lanes.branch_ends >= 1);
}

TEST_CASE("discrete elements are clustered, merged and false positives dropped",
          "[aggregate][discrete]") {
  test::SynthOptions o;
  o.false_positives = 3;
  const auto w = test::makeSynthWorld(o);
  AggregatorStats stats;
  const VectorMap map = aggregateObservations(observe(w), AggregatorParams{}, &stats);
  for (CrowdClass c : {CrowdClass::kPole, CrowdClass::kTrafficSign, CrowdClass::kGroundArrow,
                       CrowdClass::kCrosswalk, CrowdClass::kStopLine}) {
    const auto truth = ofClass(w.truth, c);
    const auto got = ofClass(map, c);
    INFO(crowdClassName(c));
    REQUIRE(got.size() == truth.size());
    for (const auto* t : truth) {
      double best = 1e300;
      const MapInstance* match = nullptr;
      for (const auto* g : got)
        if ((centre(*g) - centre(*t)).norm() < best)
          best = (centre(*g) - centre(*t)).norm(), match = g;
      CHECK(best < kDiscreteTolerance);
      CHECK(match->points.size() == (c == CrowdClass::kPole ? 1u : t->points.size()));
      if (c == CrowdClass::kPole) CHECK(match->height == Approx(5.0).margin(1e-9));
      CHECK(match->support.drives == o.drives);
    }
  }
  CHECK(stats.noise[std::size_t(CrowdClass::kPole)] >= std::size_t(o.drives));
  // random false lane lines do not become instances
  CHECK(ofClass(map, CrowdClass::kLaneLine).size() == 3);
}

TEST_CASE("aggregation is deterministic", "[aggregate]") {
  test::SynthOptions o;
  o.fork = true;
  const auto w = test::makeSynthWorld(o);
  const auto set = observe(w);
  const VectorMap a = aggregateObservations(set, AggregatorParams{});
  const VectorMap b = aggregateObservations(set, AggregatorParams{});
  REQUIRE(a.instances.size() == b.instances.size());
  for (std::size_t i = 0; i < a.instances.size(); ++i)
    CHECK(a.instances[i].points == b.instances[i].points);
}

TEST_CASE("collecting observations rejects odom LSMs and mixed origins", "[aggregate][errors]") {
  test::SynthOptions o;
  o.drives = 2;
  auto w = test::makeSynthWorld(o);
  w.lsms[1].origin->lat += 1e-4;
  try {
    collectObservations(w.lsms, {"a.cbor", "b.cbor"});
    FAIL("origin mismatch accepted");
  } catch (const InputError& e) {
    CHECK_THAT(e.what(), Catch::Contains("b.cbor"));
    CHECK_THAT(e.what(), Catch::Contains("a.cbor"));
    CHECK_THAT(e.what(), Catch::Contains("origin"));
  }
  w = test::makeSynthWorld(o);
  w.lsms[0].frame = LsmFrame::kOdom;
  CHECK_THROWS_AS(collectObservations(w.lsms, {"a.cbor", "b.cbor"}), InputError);
  CHECK_THROWS_AS(collectObservations({}, {}), InputError);
}

TEST_CASE("stage-1 comparisons per lane piece do not grow with the drives", "[aggregate][lanes]") {
  // With every piece compared with every other of its tile, the comparisons per piece grow as the
  // drives (O(n^2) per place). Compared with pieces of at most partner_drives other drives they
  // stay bounded, and the map keeps its three lines on the truth.
  std::map<int, double> per_piece;
  for (int drives : {6, 30}) {
    test::SynthOptions o = lanesOnly();
    o.drives = drives;
    const auto [w, map, stats] = aggregateLanes(o);
    per_piece[drives] = double(stats.lanes.comparisons) / double(stats.lanes.pieces);
    WARN(drives << " drives: " << stats.lanes.comparisons << " comparisons for "
                << stats.lanes.pieces << " pieces");
    // The lines on the truth: each point within 3 sigma of ONE observation's lateral error
    // (0.065 m: drive 0.05, element 0.03, point 0.03), the mean within half kLanePointTolerance.
    // Not every point within kLanePointTolerance (1.5 sigma of one observation): with 6 drives
    // that held for one draw of the noise and not for another (0.102 m).
    constexpr double kOneObservationSigma = 0.065;  // m
    const auto lanes = ofClass(map, CrowdClass::kLaneLine);
    CHECK(lanes.size() == 3);
    double sum = 0, worst = 0;
    int n = 0;
    for (const auto* l : lanes)
      for (const auto& p : l->points) {
        const double d = distanceToTruth(p, w.truth, CrowdClass::kLaneLine);
        CHECK(d < 3 * kOneObservationSigma);
        sum += d;
        worst = std::max(worst, d);
        ++n;
      }
    WARN(drives << " drives: lane points to the truth: mean " << sum / std::max(n, 1) << " m, max "
                << worst << " m");
    CHECK(n > 0);
    CHECK(sum / std::max(n, 1) < 0.5 * kLanePointTolerance);
  }
  // a piece tests the pieces of its own and partner_drives other drives whose boxes meet its own
  // (the same line and, in tiles where lines run diagonally, its neighbours: 3 at most)
  const int k = AggregatorParams{}.lanes.partner_drives;
  CHECK(per_piece[30] <= 3.0 * (k + 1));
  CHECK(per_piece[30] <= 1.3 * per_piece[6]);
}

TEST_CASE("a stop line seen whole by some drives and in part by others is one stop line",
          "[aggregate][stop_line]") {
  // A 7 m stop line along y at x = 50: 12 drives see it whole, 8 only its first 1.5 m (a camera
  // sees the end of a crossing road's stop line while turning, simulate observes that part).
  // Midpoint distance put the pieces (midpoints 2.75 m from the line's) in a cluster of their
  // own, and averaging the ends shortened the line.
  constexpr double kEndTolerance = 0.1;  // m, merged ends to the true ends (3 cm point noise)
  std::mt19937 rng(9);
  std::normal_distribution<double> noise(0.0, 0.03);
  std::vector<Observation> items;
  for (int d = 0; d < 20; ++d) {
    Observation o;
    o.drive = d;
    o.cls = CrowdClass::kStopLine;
    o.confidence = 0.8;
    const double end = d < 12 ? 7.0 : 1.5;
    const Eigen::Vector2d n0 = mapfuse::test::drawVector<Eigen::Vector2d>(noise, rng);
    const Eigen::Vector2d n1 = mapfuse::test::drawVector<Eigen::Vector2d>(noise, rng);
    o.points = {Vec3(50 + n0.x(), 0 + n0.y(), 0), Vec3(50 + n1.x(), end + n1.y(), 0)};
    items.push_back(o);
  }
  std::vector<std::size_t> idx(items.size());
  for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  const auto merged = mergeDiscrete(items, idx, CrowdClass::kStopLine, DiscreteMergeParams{}, 20,
                                    AggregatorParams{}.lanes.partner_drives);
  REQUIRE(merged.size() == 1);
  CHECK(merged[0].support.drives == 20);
  const Vec3 a = merged[0].points.front(), b = merged[0].points.back();
  const double lo = std::min(a.y(), b.y()), hi = std::max(a.y(), b.y());
  CHECK(lo == Approx(0.0).margin(kEndTolerance));
  CHECK(hi == Approx(7.0).margin(kEndTolerance));
  CHECK(a.x() == Approx(50.0).margin(kEndTolerance));
}
