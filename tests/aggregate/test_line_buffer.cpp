// aggregate::mitreBuffer against boost::geometry::buffer (the polygon it replaces in stage 1 of
// lane instantiation): same area, same overlap areas with other pieces.
#include <boost/geometry.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <catch2/catch.hpp>
#include <random>

#include "aggregate/line_buffer.hpp"
#include "aggregate/polygon_overlap.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;
using namespace mapfuse::aggregate;
namespace bg = boost::geometry;

namespace {
using P2 = bg::model::d2::point_xy<double>;
using Poly2 = bg::model::polygon<P2>;
using MPoly2 = bg::model::multi_polygon<Poly2>;
constexpr double kWidth = 0.2;  // m, stage-1 buffer half width (aggregate default)
// Relative. Boost rounds the buffer's corners to an integer grid and leaves out the joins of
// nearly collinear segments (its offset line then skips a vertex); measured here: areas within
// 5e-7, overlap areas within 1.4e-4 (stage 1 compares them with 0.3 of the smaller area).
constexpr double kAreaRel = 1e-6, kOverlapRel = 5e-4;

MPoly2 boostBuffer(const std::vector<Eigen::Vector2d>& line, double w) {
  bg::model::linestring<P2> l;
  for (const auto& p : line) l.emplace_back(p.x(), p.y());
  MPoly2 out;
  bg::buffer(l, out, bg::strategy::buffer::distance_symmetric<double>(w),
             bg::strategy::buffer::side_straight(), bg::strategy::buffer::join_miter(),
             bg::strategy::buffer::end_flat(), bg::strategy::buffer::point_circle(8));
  return out;
}

OverlapPolygon overlapOf(const MPoly2& mp) {
  std::vector<std::vector<Eigen::Vector2d>> rings;
  for (const auto& poly : mp) {
    rings.emplace_back();
    for (const auto& q : poly.outer()) rings.back().emplace_back(bg::get<0>(q), bg::get<1>(q));
  }
  return OverlapPolygon(rings, Eigen::Vector2d::Zero());
}

// A lane-line-like piece: ~8 m, points every 0.75 m, noise and a gentle curve.
std::vector<Eigen::Vector2d> piece(std::mt19937& rng, double y0, double curvature) {
  std::normal_distribution<double> noise(0.0, 0.03);
  std::vector<Eigen::Vector2d> l;
  for (double x = 0; x <= 8.0; x += 0.75) l.emplace_back(x, y0 + curvature * x * x + noise(rng));
  return l;
}
}  // namespace

TEST_CASE("mitre buffer is Boost's buffer polygon for gently curving lines",
          "[aggregate][buffer]") {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> curv(-0.02, 0.02), off(-0.3, 0.3);
  int compared = 0;
  for (int k = 0; k < 200; ++k) {
    // draws named in a fixed order (the last argument's first, as gcc evaluated the calls)
    const auto a = piece(rng, 0.0, curv(rng));
    const double curv_b = curv(rng), off_b = off(rng);
    const auto b = piece(rng, off_b, curv_b);
    const auto ra = mitreBuffer(a, kWidth), rb = mitreBuffer(b, kWidth);
    REQUIRE(ra.has_value());
    REQUIRE(rb.has_value());
    const MPoly2 ba = boostBuffer(a, kWidth), bb = boostBuffer(b, kWidth);
    CHECK(ringArea(*ra) == Approx(bg::area(ba)).epsilon(kAreaRel));
    const OverlapPolygon oa({*ra}, Eigen::Vector2d::Zero()), ob({*rb}, Eigen::Vector2d::Zero());
    const auto ours = intersectionArea(oa, ob),
               theirs = intersectionArea(overlapOf(ba), overlapOf(bb));
    if (ours && theirs) {
      CHECK(*ours == Approx(*theirs).epsilon(kOverlapRel));
      ++compared;
    }
  }
  CHECK(compared >= 190);
}

TEST_CASE("mitre buffer declines lines Boost must build", "[aggregate][buffer]") {
  CHECK_FALSE(mitreBuffer({{0, 0}}, kWidth).has_value());                  // one point
  CHECK_FALSE(mitreBuffer({{0, 0}, {0, 0}, {1, 0}}, kWidth).has_value());  // repeated point
  CHECK_FALSE(mitreBuffer({{0, 0}, {1, 0}, {1, 1}}, kWidth).has_value());  // 90 deg turn
  // a 2.5 cm segment between two 30 deg turns: the inner corners cut more than its length
  CHECK_FALSE(mitreBuffer({{0, 0}, {1, 0}, {1.022, 0.0125}, {2, 0.6}}, kWidth).has_value());
  // a tight circle: small turns, too much turning in all
  std::vector<Eigen::Vector2d> circle;
  for (int i = 0; i < 20; ++i) circle.emplace_back(3 * std::cos(0.3 * i), 3 * std::sin(0.3 * i));
  CHECK_FALSE(mitreBuffer(circle, kWidth).has_value());
  // a straight line: a rectangle of 2 w x length
  const auto r = mitreBuffer({{0, 0}, {5, 0}}, kWidth);
  REQUIRE(r.has_value());
  CHECK(ringArea(*r) == Approx(5 * 2 * kWidth));
}
