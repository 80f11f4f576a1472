#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "mapfuse/vehicle/camera.hpp"
#include "mapfuse/vehicle/triangulation.hpp"
#include "support/test_support.hpp"
#include "synthetic_camera.hpp"

using namespace mapfuse;
using namespace mapfuse::vehicle;

namespace {
constexpr double kTriangulationTol = 0.3;  // m, acceptance for elements within 30 m, >= 5 frames
constexpr double kPixelNoise = 1.0;        // px, 1-sigma

/// Level camera on a vehicle driving along body x, `step` m per frame from x = start.
std::vector<TrackObservation> observe(const Eigen::Vector3d& P, int frames, double step,
                                      std::mt19937_64& rng, double noise, double start = 0.0) {
  std::normal_distribution<double> n(0.0, noise);
  std::vector<TrackObservation> out;
  for (int i = 0; i < frames; ++i) {
    Pose3 T_world_cam = Pose3::Identity();
    T_world_cam.linear() = levelCameraToBodyRotation();
    T_world_cam.translation() = Eigen::Vector3d(start + i * step, 0.0, 1.5);
    const auto px = projectPoint(test::syntheticK(), T_world_cam.inverse() * P);
    if (!px) continue;
    out.push_back({T_world_cam, *px + mapfuse::test::drawVector<Eigen::Vector2d>(n, rng)});
  }
  return out;
}
}  // namespace

TEST_CASE("aerial triangulation is within 0.3 m for elements within 30 m seen in 5 frames") {
  std::mt19937_64 rng(42);
  TriangulationSettings s;
  double worst = 0.0;
  // The vehicle approaches each element from 30 m down to 6 m ahead: 5 frames 6 m apart.
  for (const Eigen::Vector3d& P :
       {Eigen::Vector3d(30.0, 4.0, 5.0), Eigen::Vector3d(30.0, -6.0, 3.0),
        Eigen::Vector3d(30.0, 5.0, 6.5), Eigen::Vector3d(30.0, 3.5, 2.0)}) {
    const auto obs = observe(P, 5, 6.0, rng, kPixelNoise);
    REQUIRE(obs.size() == 5);
    const auto r = triangulateTrack(test::syntheticK(), obs, s);
    REQUIRE(r.ok);
    CHECK(r.converged);
    worst = std::max(worst, (r.p_world - P).norm());
    CHECK(r.rms < 3.0 * kPixelNoise);
  }
  CHECK(worst <= kTriangulationTol);
}

TEST_CASE("triangulation is robust to one gross outlier (Huber loss)") {
  std::mt19937_64 rng(3);
  const Eigen::Vector3d P(18.0, 4.0, 4.0);
  auto obs = observe(P, 8, 1.0, rng, 0.5);
  obs[3].pixel += Eigen::Vector2d(25.0, -20.0);
  TriangulationSettings s;
  s.max_reprojection_rms = 50.0;
  const auto r = triangulateTrack(test::syntheticK(), obs, s);
  REQUIRE(r.ok);
  CHECK((r.p_world - P).norm() <= kTriangulationTol);
}

TEST_CASE("tracks with too little parallax or too few frames are rejected") {
  std::mt19937_64 rng(5);
  const Eigen::Vector3d P(60.0, 0.5, 3.0);  // straight ahead, far: tiny parallax
  const auto obs = observe(P, 4, 0.05, rng, 0.0);
  const auto r = triangulateTrack(test::syntheticK(), obs, TriangulationSettings{});
  CHECK_FALSE(r.ok);
  CHECK(r.reason == "parallax");
  const auto few = observe(Eigen::Vector3d(20, 4, 3), 2, 1.0, rng, 0.0);
  const auto r2 = triangulateTrack(test::syntheticK(), few, TriangulationSettings{});
  CHECK_FALSE(r2.ok);
  CHECK(r2.reason == "observations");
}

TEST_CASE("tracks never seen within max_range are rejected, closer ones kept", "[vehicle]") {
  std::mt19937_64 rng(8);
  const Eigen::Vector3d P(45.0, 8.0, 2.5);  // a sign the vehicle turns away from
  TriangulationSettings s;
  s.max_range = 30.0;
  // seen from 40 m down to 34 m ahead (7 frames 1 m apart): enough parallax, too far
  const auto far = observe(P, 7, 1.0, rng, kPixelNoise, 5.0);
  REQUIRE(far.size() == 7);
  const auto r = triangulateTrack(test::syntheticK(), far, s);
  CHECK_FALSE(r.ok);
  CHECK(r.reason == "range");
  CHECK(r.nearest_range > s.max_range);
  // the same sign passed by: last seen ~13 m away
  const auto near = observe(P, 8, 4.0, rng, kPixelNoise, 5.0);
  const auto r2 = triangulateTrack(test::syntheticK(), near, s);
  REQUIRE(r2.ok);
  CHECK(r2.nearest_range < s.max_range);
  CHECK((r2.p_world - P).norm() <= kTriangulationTol);
  // max_range 0: no range test
  s.max_range = 0.0;
  CHECK(triangulateTrack(test::syntheticK(), far, s).reason != "range");
}
