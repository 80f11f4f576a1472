// The road hides markings beyond a crest from the simulated camera (sim/road_occlusion.hpp).
#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>

#include "sim/road_occlusion.hpp"

using namespace mapfuse;

namespace {
constexpr double kCrestRadius = 150.0;  // m, vertical radius of the crest z = -x²/2R
constexpr double kCameraHeight = 1.4;   // m above the body origin (on the road)

/// Body on the crest at x: origin on the road, x axis along its tangent.
Pose3 bodyOnCrest(double x) {
  Pose3 T = Pose3::Identity();
  T.linear() = Eigen::AngleAxisd(std::atan(x / kCrestRadius), Eigen::Vector3d::UnitY()).matrix();
  T.translation() = Eigen::Vector3d(x, 0.0, -x * x / (2.0 * kCrestRadius));
  return T;
}
double crestZ(double x) {
  return -x * x / (2.0 * kCrestRadius);
}
// m: points whose sight line passes within this of the road are not judged (tolerance 0.02 m,
// and the road between two poses taken flat: 0.5²/8R = 0.2 mm)
constexpr double kClearMargin = 0.05;
}  // namespace

TEST_CASE("road occlusion: beyond a crest hidden, before it seen, as the sight line says") {
  // A drive over the crest top at x = 0, a pose every 0.5 m from x = -30 m; the camera at the
  // first pose. Oracle: a road point is seen when the straight sight line to it stays above the
  // road everywhere between (the crest is the same across the road, so y does not matter).
  std::vector<Pose3> poses;
  for (double x = -30.0; x <= 60.0; x += 0.5) poses.push_back(bodyOnCrest(x));
  const sim::RoadOcclusion occlusion(poses, 1);
  const Eigen::Vector3d cam = poses[0] * Eigen::Vector3d(0.0, 0.0, kCameraHeight);
  auto clearance = [&](double x) {  // least height of the sight line above the road, m
    double least = 1e300;
    const double stop = 1.0 - 1.0 / std::abs(x - cam.x());  // up to 1 m before the point
    for (double u = 0.02; u < stop; u += 0.001) {
      const double xs = cam.x() + u * (x - cam.x());
      least = std::min(least, cam.z() + u * (crestZ(x) - cam.z()) - crestZ(xs));
    }
    return least;
  };
  int seen = 0, hidden = 0;
  for (double x = -25.0; x <= 40.0; x += 0.25) {
    const double c = clearance(x);
    if (std::abs(c) < kClearMargin) continue;  // at the horizon either answer is right
    const bool h = occlusion.hidden(0, cam, Eigen::Vector3d(x, 3.0, crestZ(x)), 100.0);
    INFO("x " << x << " clearance " << c);
    CHECK(h == (c < 0.0));
    (c < 0.0 ? hidden : seen)++;
  }
  CHECK(seen > 20);  // both kinds of points were tried
  CHECK(hidden > 20);
}

TEST_CASE("road occlusion: on a flat road nothing within range is hidden") {
  std::vector<Pose3> poses;
  for (double x = 0.0; x <= 60.0; x += 0.5) {
    Pose3 T = Pose3::Identity();
    T.translation() = Eigen::Vector3d(x, 0.0, 0.0);
    poses.push_back(T);
  }
  const sim::RoadOcclusion occlusion(poses, 2);
  const Eigen::Vector3d cam(1.8, 0.0, kCameraHeight);
  for (double x = 4.0; x <= 40.0; x += 3.0)
    for (const double y : {-5.0, 0.0, 5.0})
      CHECK_FALSE(occlusion.hidden(0, cam, Eigen::Vector3d(x, y, 0.0), 100.0));
}
