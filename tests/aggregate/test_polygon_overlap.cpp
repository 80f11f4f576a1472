// intersectionArea (aggregate/polygon_overlap) against Boost.Geometry's overlay
// (bg::intersection + bg::area) as the independent reference. The reference runs in 50-digit
// arithmetic (Boost.Multiprecision): in double, Boost 1.74 places intersection points up to
// ~1e-7 m off (a bar across a holed square: 8.7274043743 m² instead of the exact
// 8.7274038462 m²), far above the 1e-9 m² this routine is checked to.
#if defined(__GNUC__) && !defined(__clang__)  // a gcc warning clang does not know
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"  // Boost.Geometry buffer, as in the lib
#endif
#include <boost/geometry.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "aggregate/polygon_overlap.hpp"
#include "support/test_support.hpp"

using namespace mapfuse::aggregate;
namespace bg = boost::geometry;
using P2 = bg::model::d2::point_xy<double>;
using Line2 = bg::model::linestring<P2>;
using Poly2 = bg::model::polygon<P2>;  // clockwise outer rings, closed
using MPoly2 = bg::model::multi_polygon<Poly2>;
using V2 = Eigen::Vector2d;
using Real = boost::multiprecision::cpp_bin_float_50;
using MPolyX = bg::model::multi_polygon<bg::model::polygon<bg::model::d2::point_xy<Real>>>;

namespace {

constexpr double kAreaTolerance = 1e-9;  // m², |ours - Boost| (areas here are 0.1 .. 100 m²)
constexpr double kBufferWidth = 0.2;     // m, as lane instantiation stage 1

MPoly2 fromWkt(const std::string& wkt) {
  MPoly2 mp;
  bg::read_wkt(wkt, mp);
  bg::correct(mp);  // Boost's orientation and closure
  return mp;
}

// Rings of a multipolygon; `ccw`: reversed, i.e. counter-clockwise outer rings, clockwise holes.
OverlapPolygon toOverlap(const MPoly2& mp, const V2& origin, bool ccw = false) {
  std::vector<std::vector<V2>> rings;
  auto add = [&](const auto& ring) {
    rings.emplace_back();
    for (const auto& q : ring) rings.back().emplace_back(bg::get<0>(q), bg::get<1>(q));
    if (ccw) std::reverse(rings.back().begin(), rings.back().end());
  };
  for (const auto& poly : mp) {
    add(poly.outer());
    for (const auto& inner : poly.inners()) add(inner);
  }
  return OverlapPolygon(rings, origin);
}

// Area of a ∩ b by Boost.Geometry in 50-digit arithmetic (the double inputs are exact in it).
double boostArea(const MPoly2& a, const MPoly2& b) {
  MPolyX ax, bx, both;
  bg::convert(a, ax);
  bg::convert(b, bx);
  bg::intersection(ax, bx, both);
  return double(bg::area(both));
}

// Every orientation combination gives Boost's area (the configuration is not degenerate).
void checkExact(const MPoly2& a, const MPoly2& b, const V2& origin = V2(0, 0)) {
  const double ref = boostArea(a, b);
  for (int combo = 0; combo < 4; ++combo) {
    INFO("a ccw " << (combo & 1) << ", b ccw " << (combo >> 1) << ", Boost " << ref);
    const auto got =
        intersectionArea(toOverlap(a, origin, combo & 1), toOverlap(b, origin, combo >> 1));
    REQUIRE(got.has_value());
    CHECK(std::abs(*got - ref) <= kAreaTolerance);
  }
}

// Touching configurations: the area is either Boost's or reported as degenerate (nullopt).
// Returns the number of nullopt answers over the orientation combinations and both orders.
int checkExactOrDegenerate(const MPoly2& a, const MPoly2& b) {
  const double ref = boostArea(a, b);
  int degenerate = 0;
  for (int combo = 0; combo < 4; ++combo) {
    const OverlapPolygon pa = toOverlap(a, V2(0, 0), combo & 1);
    const OverlapPolygon pb = toOverlap(b, V2(0, 0), combo >> 1);
    for (const auto& got : {intersectionArea(pa, pb), intersectionArea(pb, pa)}) {
      INFO("combo " << combo << ", Boost " << ref);
      if (got)
        CHECK(std::abs(*got - ref) <= kAreaTolerance);
      else
        ++degenerate;
    }
  }
  return degenerate;
}

// A random walk of `steps` segments from `start`, heading `heading` (rad), turning by up to
// ±`curl` (rad) per step.
Line2 randomWalk(std::mt19937& rng, const V2& start, double heading, int steps,
                 double curl = 0.35) {
  std::uniform_real_distribution<double> len(0.2, 1.2), turn(-curl, curl);
  Line2 line{P2(start.x(), start.y())};
  V2 p = start;
  for (int i = 0; i < steps; ++i) {
    heading += turn(rng);
    p += len(rng) * V2(std::cos(heading), std::sin(heading));
    line.emplace_back(p.x(), p.y());
  }
  return line;
}

// ±kBufferWidth, flat ends and mitre joins, as lane instantiation stage 1.
MPoly2 bufferLine(const Line2& line) {
  MPoly2 out;
  bg::buffer(line, out, bg::strategy::buffer::distance_symmetric<double>(kBufferWidth),
             bg::strategy::buffer::side_straight(), bg::strategy::buffer::join_miter(),
             bg::strategy::buffer::end_flat(), bg::strategy::buffer::point_circle(8));
  return out;
}

}  // namespace

TEST_CASE("intersectionArea matches Boost on random buffered polylines", "[aggregate][overlap]") {
  std::mt19937 rng(20231123);
  std::uniform_real_distribution<double> unit(0.0, 1.0), offset(-0.35, 0.35);
  std::uniform_int_distribution<int> steps(2, 25);
  const V2 corner(230.0, -140.0);  // a tile corner in ENU: the local origin, as in stage 1
  constexpr int kPairs = 3000;
  int overlapping = 0, with_holes = 0, degenerate = 0;
  double worst = 0.0;
  for (int k = 0; k < kPairs; ++k) {
    // two walks starting near each other in roughly the same direction: like two observations
    // of one lane line; every fourth pair curls, crossing and looping over itself
    const V2 start = corner + 10.0 * mapfuse::test::drawVector<V2>(unit, rng);
    const double heading = 2 * M_PI * unit(rng), curl = k % 4 == 3 ? 1.2 : 0.35;
    const MPoly2 a = bufferLine(randomWalk(rng, start, heading, steps(rng), curl));
    // draws named in a fixed order (the last argument's first, as gcc evaluated the call)
    const int steps_b = steps(rng);
    const double heading_b = heading + 0.3 * offset(rng);
    const V2 start_b = start + mapfuse::test::drawVector<V2>(offset, rng);
    const MPoly2 b = bufferLine(randomWalk(rng, start_b, heading_b, steps_b, curl));
    for (const auto* mp : {&a, &b})
      for (const auto& poly : *mp) with_holes += poly.inners().empty() ? 0 : 1;
    const double ref = boostArea(a, b);
    const OverlapPolygon pa = toOverlap(a, corner), pb = toOverlap(b, corner);
    CHECK(std::abs(pa.area() - bg::area(a)) <= kAreaTolerance);
    const auto ab = intersectionArea(pa, pb), ba = intersectionArea(pb, pa);
    REQUIRE(ab.has_value() == ba.has_value());
    if (!ab) {
      ++degenerate;
      continue;
    }
    INFO("pair " << k << ": Boost " << ref << ", ours " << *ab << " / " << *ba);
    CHECK(std::abs(*ab - ref) <= kAreaTolerance);
    CHECK(std::abs(*ba - ref) <= kAreaTolerance);
    worst = std::max({worst, std::abs(*ab - ref), std::abs(*ba - ref)});
    if (ref > 0.05) ++overlapping;
  }
  INFO("overlapping " << overlapping << ", polygons with holes " << with_holes << ", degenerate "
                      << degenerate << ", worst " << worst << " m²");
  CHECK(overlapping > kPairs / 2);  // the test exercises real overlaps,
  CHECK(with_holes > 0);            // self-overlapping walks (buffer polygons with holes),
  CHECK(degenerate == 0);           // and random input is never degenerate
}

TEST_CASE("intersectionArea handles polygons with holes", "[aggregate][overlap]") {
  const MPoly2 holed = fromWkt("MULTIPOLYGON(((0 0,10 0,10 10,0 10,0 0),(3 3,7 3,7 7,3 7,3 3)))");
  // a bar across the hole
  checkExact(holed, fromWkt("MULTIPOLYGON(((-1.3 4.1,11.7 4.6,11.6 5.9,-1.2 5.7,-1.3 4.1)))"));
  // a rotated square around the hole, partly in it
  checkExact(holed, fromWkt("MULTIPOLYGON(((5 1.5,8.5 5,5 8.5,1.5 5,5 1.5)))"));
  // another holed polygon, shifted: holes overlap holes and rings
  checkExact(holed, fromWkt("MULTIPOLYGON(((1.1 1.3,11.1 1.3,11.1 11.3,1.1 11.3,1.1 1.3),"
                            "(4.1 4.3,8.1 4.3,8.1 8.3,4.1 8.3,4.1 4.3)))"));
  // two parts, one in the hole and one across the outer ring
  checkExact(holed, fromWkt("MULTIPOLYGON(((4 4.2,6 4.4,5.1 6,4 4.2)),"
                            "((9.1 -1,12 -1.2,11 2,9.1 -1)))"));
  // inside the hole only: nothing
  const auto in_hole =
      intersectionArea(toOverlap(holed, V2(0, 0)),
                       toOverlap(fromWkt("MULTIPOLYGON(((4 4,6 4.5,5 6,4 4)))"), V2(0, 0)));
  REQUIRE(in_hole.has_value());
  CHECK(*in_hole == 0.0);
}

TEST_CASE("intersectionArea is zero for disjoint polygons", "[aggregate][overlap]") {
  const MPoly2 ell = fromWkt("MULTIPOLYGON(((0 0,6 0,6 2,2 2,2 6,0 6,0 0)))");
  const MPoly2 far = fromWkt("MULTIPOLYGON(((20 20,21 20,21 21,20 21,20 20)))");
  const MPoly2 notch = fromWkt("MULTIPOLYGON(((3 3,5.5 3.2,5 5.3,3.1 5,3 3)))");  // boxes overlap
  for (const auto* b : {&far, &notch}) {
    const auto got = intersectionArea(toOverlap(ell, V2(0, 0)), toOverlap(*b, V2(0, 0)));
    REQUIRE(got.has_value());
    CHECK(*got == 0.0);
    CHECK(boostArea(ell, *b) == 0.0);
  }
  const auto empty = intersectionArea(OverlapPolygon(), toOverlap(ell, V2(0, 0)));
  REQUIRE(empty.has_value());
  CHECK(*empty == 0.0);
}

TEST_CASE("intersectionArea of nested polygons is the inner area", "[aggregate][overlap]") {
  const MPoly2 outer = fromWkt("MULTIPOLYGON(((0 0,10 0.5,9.5 10,0.3 9,0 0)))");
  const MPoly2 inner = fromWkt("MULTIPOLYGON(((2 2,7 2.5,6 7,2 6,2 2)))");
  checkExact(outer, inner);
  checkExact(inner, outer);
  const auto got = intersectionArea(toOverlap(outer, V2(0, 0)), toOverlap(inner, V2(0, 0)));
  REQUIRE(got.has_value());
  CHECK(std::abs(*got - bg::area(inner)) <= kAreaTolerance);
}

TEST_CASE("intersectionArea of identical polygons is their area", "[aggregate][overlap]") {
  std::mt19937 rng(7);
  const MPoly2 a = bufferLine(randomWalk(rng, V2(1, 2), 0.4, 12));
  const OverlapPolygon pa = toOverlap(a, V2(0, 0));
  const auto same = intersectionArea(pa, toOverlap(a, V2(0, 0)));
  REQUIRE(same.has_value());
  CHECK(std::abs(*same - bg::area(a)) <= kAreaTolerance);
  // the same region given counter-clockwise (another first vertex): exact or reported
  checkExactOrDegenerate(a, a);
}

TEST_CASE("intersectionArea with shared edges or touching vertices is exact or reported",
          "[aggregate][overlap]") {
  const MPoly2 square = fromWkt("MULTIPOLYGON(((0 0,2 0,2 2,0 2,0 0)))");
  // shared edge, touching corner, collinear overlapping edges, a vertex on an edge (outside and
  // inside), a vertex 1e-12 m from an edge
  const char* touching[] = {
      "MULTIPOLYGON(((2 0,4 0,4 2,2 2,2 0)))",
      "MULTIPOLYGON(((2 2,3 2,3 3,2 3,2 2)))",
      "MULTIPOLYGON(((1 0,3 0,3 1,1 1,1 0)))",
      "MULTIPOLYGON(((2 1,3 0.5,3 1.5,2 1)))",
      "MULTIPOLYGON(((2 1,1 0.5,1 1.5,2 1)))",
      "MULTIPOLYGON(((1.5 -1,2 0.5,1 1,1.5 -1)))",
      "MULTIPOLYGON(((2.000000000001 1,3 0.5,3 1.5,2.000000000001 1)))",
  };
  int degenerate = 0;
  for (const char* wkt : touching) {
    INFO(wkt);
    degenerate += checkExactOrDegenerate(square, fromWkt(wkt));
  }
  CHECK(degenerate > 0);  // some of these must have been recognised as degenerate
}

TEST_CASE("OverlapPolygon accepts both ring orientations", "[aggregate][overlap]") {
  const MPoly2 holed = fromWkt("MULTIPOLYGON(((0 0,10 0,10 10,0 10,0 0),(3 3,7 3,7 7,3 7,3 3)))");
  const OverlapPolygon cw = toOverlap(holed, V2(1, 1)), ccw = toOverlap(holed, V2(1, 1), true);
  CHECK(cw.area() == Approx(84.0).margin(kAreaTolerance));
  CHECK(ccw.area() == Approx(84.0).margin(kAreaTolerance));
  for (const auto* p : {&cw, &ccw}) {  // normalised: outer ring counter-clockwise, hole clockwise
    const auto rings = p->localRings();
    REQUIRE(rings.size() == 2);
    auto signedArea = [](const std::vector<V2>& r) {
      double s = 0;
      for (std::size_t i = 0; i < r.size(); ++i) {
        const V2& u = r[i];
        const V2& v = r[(i + 1) % r.size()];
        s += 0.5 * (u.x() * v.y() - u.y() * v.x());
      }
      return s;
    };
    CHECK(signedArea(rings[0]) == Approx(100.0));
    CHECK(signedArea(rings[1]) == Approx(-16.0));
  }
  // checkExact runs all four orientation combinations
  checkExact(holed, fromWkt("MULTIPOLYGON(((-1 5.2,5.3 -1.1,11 4.4,4.9 11.3,-1 5.2)))"), V2(1, 1));
}

TEST_CASE("intersectionArea refuses polygons with different origins", "[aggregate][overlap]") {
  const MPoly2 square = fromWkt("MULTIPOLYGON(((0 0,2 0,2 2,0 2,0 0)))");
  CHECK_THROWS_AS(intersectionArea(toOverlap(square, V2(0, 0)), toOverlap(square, V2(1, 0))),
                  std::invalid_argument);
}
