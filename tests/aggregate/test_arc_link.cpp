#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "aggregate/arc_link.hpp"
#include "aggregate/lane_instantiation.hpp"
#include "mapfuse/aggregate/geometry2d.hpp"
#include "mapfuse/core/vector_map.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;
using namespace mapfuse::aggregate;
using Vec3 = Eigen::Vector3d;

namespace {

constexpr double kRing = 9.0;  // m, radius of a small roundabout's lane line

// Points every 0.5 m along the ring from arc length s0 to s1 (counter-clockwise).
std::vector<Vec3> ringPiece(double s0, double s1, double radius = kRing,
                            const Vec3& centre = Vec3(20, 30, 0)) {
  std::vector<Vec3> out;
  for (double s = s0; s <= s1 + 1e-9; s += 0.5)
    out.push_back(centre + Vec3(radius * std::cos(s / radius), radius * std::sin(s / radius), 0));
  return out;
}

std::vector<Vec3> reversed(std::vector<Vec3> v) {
  std::reverse(v.begin(), v.end());
  return v;
}

}  // namespace

TEST_CASE("fitCircle2d recovers a ring from noisy points and refuses a line", "[aggregate][arc]") {
  // m: 2 cm point noise on a 12 m arc (76 deg) pins centre and radius to about 0.1 m
  constexpr double kCentreTolerance = 0.2, kRadiusTolerance = 0.2;
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 0.02);
  std::vector<Eigen::Vector2d> pts;
  for (const auto& p : ringPiece(0, 12))
    pts.push_back(p.head<2>() + mapfuse::test::drawVector<Eigen::Vector2d>(noise, rng));
  Eigen::Vector2d c;
  double r = 0;
  REQUIRE(fitCircle2d(pts, &c, &r));
  CHECK((c - Eigen::Vector2d(20, 30)).norm() < kCentreTolerance);
  CHECK(std::abs(r - kRing) < kRadiusTolerance);
  std::vector<Eigen::Vector2d> line{{0, 0}, {1, 1}, {2, 2}, {3, 3}};
  CHECK_FALSE(fitCircle2d(line, &c, &r));
  CHECK_FALSE(fitCircle2d({{0, 0}, {1, 0}}, &c, &r));
}

TEST_CASE("continuesOnArc links dashes along a ring and nothing else", "[aggregate][arc]") {
  const ArcLinkLimits limits;  // 8 m gap, 4 m radius, 0.15 m residual
  // dash a: arc 0..3 m (end at 3 m); dash b: 9..12 m (6 m gap, ~38 deg of turn)
  const auto a = ringPiece(0, 3), b = ringPiece(9, 12);
  CHECK(continuesOnArc(a, b, limits));                        // a's end -> b's start
  CHECK(continuesOnArc(reversed(b), reversed(a), limits));    // and back
  CHECK_FALSE(continuesOnArc(a, reversed(b), limits));        // b's far end, b runs back to a
  CHECK_FALSE(continuesOnArc(reversed(a), b, limits));        // a's start faces away from b
  CHECK_FALSE(continuesOnArc(a, ringPiece(15, 18), limits));  // 12 m gap > 8 m
  // a dash of a concentric ring 3.5 m further out (the neighbouring lane line)
  CHECK_FALSE(continuesOnArc(a, ringPiece(9, 12, kRing + 3.5), limits));
  // a 3 m circle is no lane line
  CHECK_FALSE(continuesOnArc(ringPiece(0, 2, 3.0), ringPiece(4, 6, 3.0), limits));
  // the bridge follows the ring, not the chord
  const auto bridge = arcBridge(a, b, 1.0);
  REQUIRE(bridge.size() >= 4);
  for (const auto& p : bridge)
    CHECK(std::abs((p - Vec3(20, 30, 0)).head<2>().norm() - kRing) < 0.01);
}

TEST_CASE("a roundabout ring observed dash by dash becomes one instance on the ring",
          "[aggregate][arc][lanes]") {
  // 10 drives see every dash (3 m dashes, 6 m gaps) of three quarters of a 9 m ring, each
  // drive offset by up to 5 cm: the straight link test (30 deg) cannot join them
  constexpr double kRingTolerance = 0.15;  // m, map centreline to the true ring
  constexpr double kMinCoverage = 0.9;     // of the observed arc from first to last dash
  std::mt19937 rng(3);
  std::normal_distribution<double> offset(0.0, 0.05);
  std::vector<Observation> items;
  const double quarter = M_PI / 2 * kRing;
  for (int d = 0; d < 10; ++d) {
    const Eigen::Vector2d xy = mapfuse::test::drawVector<Eigen::Vector2d>(offset, rng);
    const Vec3 shift(xy.x(), xy.y(), 0);
    for (double s = 0; s + 3 <= 3 * quarter; s += 9) {
      Observation o;
      o.drive = d;
      o.points = ringPiece(s, s + 3);
      for (auto& p : o.points) p += shift;
      items.push_back(o);
    }
  }
  std::vector<std::size_t> idx(items.size());
  for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  const auto lanes = instantiateLanes(items, idx, LaneInstantiationParams{}, 10);
  REQUIRE(lanes.instances.size() == 1);
  const auto& c = lanes.instances[0].centreline;
  for (const auto& p : c)
    CHECK(std::abs((p - Vec3(20, 30, 0)).head<2>().norm() - kRing) < kRingTolerance);
  const double observed =
      std::floor((3 * quarter - 3) / 9) * 9 + 3;  // first dash start .. last end
  CHECK(polylineLength(c) >= kMinCoverage * observed);
}
