#include <catch2/catch.hpp>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "mapfuse/core/error.hpp"
#include "mapfuse/vehicle/dead_reckoning.hpp"
#include "vehicle/centerline.hpp"

using namespace mapfuse;
using namespace mapfuse::vehicle;

namespace {
constexpr double kCircleTol = 0.02;  // m after a quarter circle at 100 Hz
constexpr double kCentreTol = 0.6;   // px, row centroid of a drawn line
}  // namespace

TEST_CASE("dead reckoning follows a circle and applies wheel scale and gyro bias") {
  const double v = 10.0, w = 0.1, bias = 0.01, scale = 1.05;
  std::vector<ImuSample> imu;
  std::vector<WheelSample> wheel;
  for (int i = 0; i <= 1571; ++i) {  // 15.71 s: a quarter circle
    const double t = i * 0.01;
    imu.push_back({t, Eigen::Vector3d(0, 0, w + bias), Eigen::Vector3d::Zero()});
    wheel.push_back({t, v / scale});
  }
  DeadReckoningSettings s;
  s.wheel_scale = scale;
  s.gyro_bias = Eigen::Vector3d(0, 0, bias);
  const double T = 15.70796;
  const auto poses = deadReckon(imu, wheel, {0.0, T}, s);
  const double R = v / w;
  CHECK((poses[1].translation() - Eigen::Vector3d(R, R, 0)).norm() < kCircleTol);
  CHECK(poses[0].isApprox(Pose3::Identity()));

  const auto kf = selectKeyframes(deadReckon(imu, wheel, {0, 1, 2, 3, 4, 5, 6}, s), 15.0, 1.0);
  CHECK(kf == std::vector<std::size_t>{0, 2, 4, 6});  // 10 m per second, 15 m spacing

  CHECK_THROWS_AS(deadReckon({}, wheel, {0.0}, s), InputError);
  auto bad = imu;
  std::swap(bad[3], bad[4]);
  CHECK_THROWS_AS(deadReckon(bad, wheel, {0.0}, s), InputError);
}

TEST_CASE("mask components thin to row centroids and dashes stay separate") {
  cv::Mat mask(200, 300, CV_8UC1, cv::Scalar(0));
  // A slanted solid line of class 1 and two dashes of class 2.
  cv::line(mask, {100, 199}, {150, 0}, cv::Scalar(1), 7);
  cv::line(mask, {250, 190}, {240, 140}, cv::Scalar(2), 5);
  cv::line(mask, {236, 110}, {228, 70}, cv::Scalar(2), 5);
  cv::circle(mask, {20, 20}, 1, cv::Scalar(1), -1);  // speck below min_area
  const auto solid = extractComponents(mask, 1, ThinMode::kRows, 30);
  REQUIRE(solid.size() == 1);
  for (const auto& p : solid[0].pixels) {
    if (p.y() < 5 || p.y() > 195) continue;  // line caps
    const double x_true = 100.0 + 50.0 * (199.0 - p.y()) / 199.0;
    CHECK(std::abs(p.x() - x_true) < kCentreTol);
  }
  CHECK(solid[0].pixels.front().y() > solid[0].pixels.back().y());  // near first
  CHECK(extractComponents(mask, 2, ThinMode::kRows, 30).size() == 2);
  CHECK(extractComponents(mask, 3, ThinMode::kRows, 30).empty());
  const auto hull = extractComponents(mask, 1, ThinMode::kHull, 30);
  REQUIRE(hull.size() == 1);
  CHECK(hull[0].pixels.size() >= 4);
}
