#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "aggregate/bezier_fit.hpp"
#include "mapfuse/aggregate/dbscan.hpp"
#include "aggregate/discrete_merge.hpp"
#include "mapfuse/aggregate/geometry2d.hpp"
#include "mapfuse/io/vector_map_io.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;
using namespace mapfuse::aggregate;
using Vec3 = Eigen::Vector3d;

TEST_CASE("DBSCAN finds density-connected clusters and noise", "[aggregate][dbscan]") {
  // 1D points: two dense groups and one isolated point; eps = 1.0, MinPts = 3
  const std::vector<double> x = {0.0, 0.5, 1.0, 1.5, 10.0, 10.4, 10.9, 30.0};
  auto neighbours = [&](std::size_t i) {
    std::vector<std::size_t> out;
    for (std::size_t j = 0; j < x.size(); ++j)
      if (j != i && std::abs(x[i] - x[j]) <= 1.0) out.push_back(j);
    return out;
  };
  const auto r = dbscan(x.size(), 3, neighbours);
  CHECK(r.num_clusters == 2);
  CHECK(r.num_noise == 1);
  CHECK(r.labels[0] == r.labels[3]);  // chained through 0.5 and 1.0
  CHECK(r.labels[4] == r.labels[6]);
  CHECK(r.labels[0] != r.labels[4]);
  CHECK(r.labels[7] == -1);
  // MinPts = 1: every object is core, the isolated point becomes its own cluster
  CHECK(dbscan(x.size(), 1, neighbours).num_clusters == 3);
}

TEST_CASE("Bezier chain fits a straight line with one segment and an arc within the limit",
          "[aggregate][bezier]") {
  constexpr double kMaxDeviation = 0.05;  // m
  BezierFitParams params;
  params.max_deviation = kMaxDeviation;
  std::vector<Vec3> straight;
  for (int i = 0; i <= 100; ++i) straight.push_back({0.5 * i, 0.25 * i, 0.0});
  const auto line = fitBezierChain(straight, params);
  REQUIRE(line.chain.size() == 1);
  CHECK(line.max_deviation < 1e-6);
  CHECK((line.chain.front()[0] - straight.front()).norm() < 1e-12);
  CHECK((line.chain.front()[3] - straight.back()).norm() < 1e-12);

  // a 180 deg arc of radius 30 m: one cubic cannot hold it within 5 cm, a chain must
  std::vector<Vec3> arc;
  const double R = 30.0;
  for (int i = 0; i <= 300; ++i) {
    const double a = M_PI * i / 300.0;
    arc.push_back({R * std::cos(a), R * std::sin(a), 0.0});
  }
  const auto fit = fitBezierChain(arc, params);
  CHECK(fit.chain.size() >= 2);
  CHECK(fit.max_deviation <= kMaxDeviation);
  // independent check: dense samples of the chain stay on the circle
  double worst = 0.0;
  for (const auto& p : io::sampleBezierChain(fit.chain, 0.05))
    worst = std::max(worst, std::abs(p.head<2>().norm() - R));
  CHECK(worst <= kMaxDeviation);
  // joints are shared (C0) and tangent-continuous (G1)
  for (std::size_t i = 1; i < fit.chain.size(); ++i) {
    CHECK((fit.chain[i][0] - fit.chain[i - 1][3]).norm() < 1e-12);
    const Vec3 t_in = (fit.chain[i - 1][3] - fit.chain[i - 1][2]).normalized();
    const Vec3 t_out = (fit.chain[i][1] - fit.chain[i][0]).normalized();
    CHECK(t_in.dot(t_out) > std::cos(1e-6));
  }
}

TEST_CASE("Bezier handles stay bounded when the end tangents disagree with the data",
          "[aggregate][bezier]") {
  // A short kinked piece whose end tangents (from the neighbouring metres) point across it: the
  // least-squares handle lengths explode (a 1.6 m piece of a Karlsruhe lane got handles of 150 m
  // and a 144 m ghost line). Handles longer than the chord fall back to chord / 3, and the
  // chain splits until it holds the data.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  BezierFitParams params;
  int exploded_before_bound = 0;
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<Vec3> p = {
        {0, 0, 0}, {0.8 + 0.5 * uni(rng), 0.6 * uni(rng), 0}, {1.5, 0.3 * uni(rng), 0}};
    const double chord = (p.back() - p.front()).norm();
    const Eigen::Vector2d d0 = mapfuse::test::drawVector<Eigen::Vector2d>(uni, rng);
    const Vec3 t0 = Vec3(d0.x(), d0.y(), 0).normalized();
    const Eigen::Vector2d d1 = mapfuse::test::drawVector<Eigen::Vector2d>(uni, rng);
    const Vec3 t1 = Vec3(d1.x(), d1.y(), 0).normalized();
    std::vector<double> u = {
        0.0, (p[1] - p[0]).norm() / ((p[1] - p[0]).norm() + (p[2] - p[1]).norm()), 1.0};
    const BezierSegment seg = fitCubicBezier(p, u, t0, t1, params.reparam_iterations);
    const double a = (seg[1] - seg[0]).norm(), b = (seg[2] - seg[3]).norm();
    CHECK(a <= chord + 1e-9);
    CHECK(b <= chord + 1e-9);
    if (std::max(a, b) > 0.99 * chord / 3 && std::max(a, b) < 1.01 * chord / 3)
      ++exploded_before_bound;
    // the whole chain through the same points stays near them
    const auto fit = fitBezierChain(p, params);
    for (const auto& q : io::sampleBezierChain(fit.chain, 0.05)) {
      double near = 1e9;
      for (const auto& r : p) near = std::min(near, (q - r).norm());
      CHECK(near <= chord);
    }
  }
  CHECK(exploded_before_bound > 0);  // the fallback was exercised
}

TEST_CASE("polygon IoU and rectangles", "[aggregate][geometry]") {
  const std::vector<Vec3> a = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}};
  const std::vector<Vec3> b = {{1, 0, 0}, {3, 0, 0}, {3, 1, 0}, {1, 1, 0}};
  CHECK(polygonIou2d(a, b) == Approx(1.0 / 3.0).epsilon(1e-9));  // 1 / (2 + 2 - 1)
  CHECK(polygonIou2d(a, a) == Approx(1.0));
  const std::vector<Vec3> far = {{10, 0, 0}, {11, 0, 0}, {11, 1, 0}, {10, 1, 0}};
  CHECK(polygonIou2d(a, far) == 0.0);
  // clockwise corner order gives the same IoU
  const std::vector<Vec3> cw = {b[3], b[2], b[1], b[0]};
  CHECK(polygonIou2d(a, cw) == Approx(1.0 / 3.0).epsilon(1e-9));
  // a rectangle from 6 points on its outline
  const auto r = toRectangle({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {0, 1, 0}});
  REQUIRE(r.size() == 4);
  CHECK(polygonIou2d(r, a) == Approx(1.0).epsilon(1e-9));
}

TEST_CASE("resampling and centrelines", "[aggregate][geometry]") {
  const auto r = resamplePolyline({{0, 0, 0}, {1, 0, 0}, {1, 2, 0}}, 0.5);
  REQUIRE(r.size() == 7);
  CHECK((r[2] - Vec3(1, 0, 0)).norm() < 1e-12);
  CHECK((r.back() - Vec3(1, 2, 0)).norm() < 1e-12);
  // two parallel noisy-free lines 0.2 m apart average into the middle one
  std::vector<Vec3> pts;
  for (int i = 0; i <= 40; ++i) {
    pts.push_back({0.25 * i, 0.1, 0});
    pts.push_back({0.25 * i, -0.1, 0});
  }
  const auto c = binnedCentreline(pts, 1.0);
  REQUIRE(c.size() >= 10);
  for (const auto& p : c) CHECK(std::abs(p.y()) < 1e-12);
  CHECK(distanceToPolyline2d({5, 1, 0}, c) == Approx(1.0));
}
