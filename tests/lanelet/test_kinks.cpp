#include <catch2/catch.hpp>
#include <cmath>

#include "lanelet/kinks.hpp"
#include "mapfuse/lanelet/plan.hpp"
#include "mapfuse/lanelet/settings.hpp"

using namespace mapfuse;
using Vec3 = Eigen::Vector3d;
using lanelet::detail::mengerCurvature;
using lanelet::detail::removeKinks;

namespace {
constexpr double kLanelet2Limit = 0.5;  // 1/m, lanelet2_validation's curvature_too_big
constexpr double kTol = 1e-9;

/// Largest Menger curvature over the interior vertices, and whether any vertex turns back.
std::pair<double, bool> worstBend(const std::vector<Vec3>& pts) {
  double worst = 0.0;
  bool back = false;
  for (std::size_t i = 1; i + 1 < pts.size(); ++i) {
    worst = std::max(worst, mengerCurvature(pts[i - 1], pts[i], pts[i + 1]));
    back |= (pts[i] - pts[i - 1]).head<2>().dot((pts[i + 1] - pts[i]).head<2>()) < 0;
  }
  return {worst, back};
}
}  // namespace

TEST_CASE("kinks: Menger curvature is 1/R on a circle, infinite on coincident points",
          "[lanelet]") {
  for (const double r : {2.0, 10.0, 250.0}) {
    auto at = [&](double a) { return Vec3(r * std::cos(a), r * std::sin(a), 0.0); };
    CHECK(mengerCurvature(at(0.0), at(0.3), at(0.5)) == Approx(1.0 / r).epsilon(1e-9));
  }
  CHECK(mengerCurvature({0, 0, 0}, {1, 0, 0}, {2, 0, 5}) == Approx(0.0).margin(kTol));  // xy only
  CHECK(std::isinf(mengerCurvature({0, 0, 0}, {0, 0, 0}, {1, 0, 0})));
}

TEST_CASE("kinks: a fold-back like the demo map's is removed, a real curve is kept", "[lanelet]") {
  // A lane line every 0.5 m along x, folding back at x = 10 as the demo's bound did (way -5286:
  // forward, 0.2 m back, forward again; turns of 163 and 170 degrees).
  std::vector<Vec3> line;
  for (double x = 0.0; x <= 10.0 + 1e-9; x += 0.5) line.push_back({x, 0.0, 0.0});
  line.push_back({9.8, 0.03, 0.0});
  for (double x = 10.2; x <= 20.0 + 1e-9; x += 0.5) line.push_back({x, 0.02, 0.0});
  REQUIRE(worstBend(line).first > kLanelet2Limit);
  lanelet::detail::KinkRemoval stats;
  const auto clean = removeKinks(line, 0.4, &stats);
  const auto [worst, back] = worstBend(clean);
  CHECK(worst <= 0.4);
  CHECK_FALSE(back);
  CHECK(stats.removed >= 1);
  CHECK(stats.removed <= 3);           // only the fold's vertices
  CHECK(stats.max_deviation <= 0.25);  // the 0.2 m of backtrack and the 3 cm step
  CHECK(clean.front() == line.front());
  CHECK(clean.back() == line.back());

  // A curve of radius 5 m (curvature 0.2 < 0.4), sampled every 0.5 m: every vertex stays.
  std::vector<Vec3> arc;
  for (int k = 0; k <= 30; ++k)
    arc.push_back({5.0 * std::cos(0.1 * k), 5.0 * std::sin(0.1 * k), 0});
  lanelet::detail::KinkRemoval none;
  CHECK(removeKinks(arc, 0.4, &none).size() == arc.size());
  CHECK(none.removed == 0);
  // The same curve against a limit below its curvature loses vertices until it holds.
  const auto coarse = removeKinks(arc, 0.1);
  CHECK(coarse.size() < arc.size());
  CHECK(worstBend(coarse).first <= 0.1);
}

TEST_CASE("kinks: a connector turning within metres keeps its bounds under the curvature limit",
          "[lanelet]") {
  // Road A runs east to x = 0 (lines at y = 0 and 3.5); road B leaves northwards from y = 6 (lines
  // at x = 6 and 9.5); drives turn left from one to the other over the unmarked 6 m between
  // (MONAEast at the frames level: a connector bound bent 45 degrees over 0.65 m).
  auto line = [](int64_t id, Vec3 a, Vec3 b) {
    MapInstance m;
    m.id = id;
    m.cls = CrowdClass::kLaneLine;
    for (double t = 0.0; t <= 1.0 + 1e-9; t += 0.01) m.points.push_back(a + t * (b - a));
    return m;
  };
  VectorMap map;
  map.instances = {line(1, {-50, 0, 0}, {0, 0, 0}), line(2, {-50, 3.5, 0}, {0, 3.5, 0}),
                   line(3, {6, 6, 0}, {6, 60, 0}), line(4, {9.5, 6, 0}, {9.5, 60, 0})};
  lanelet::DrivePath drive;
  for (double x = -48.0; x <= 0.0; x += 0.5) drive.push_back({x, 1.75, 0});
  for (double a = 0.05; a < M_PI / 2; a += 0.05)  // quarter circle of radius 6 about (0, 7.75)
    drive.push_back({6.0 * std::sin(a), 7.75 - 6.0 * std::cos(a), 0});
  for (double y = 7.75; y <= 58.0; y += 0.5) drive.push_back({7.75, y, 0});
  const lanelet::LaneletSettings settings;
  const lanelet::LaneletPlan plan = lanelet::planLanelets(map, {drive, drive, drive}, settings);
  REQUIRE(plan.connectors.size() == 1);
  for (const auto* bound : {&plan.connectors[0].left, &plan.connectors[0].right}) {
    INFO("connector bound of " << bound->size() << " points");
    CHECK(worstBend(*bound).first <= settings.max_curvature);
    CHECK_FALSE(worstBend(*bound).second);
  }
}
