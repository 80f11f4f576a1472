#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "mapfuse/vehicle/ground_ranging.hpp"
#include "mapfuse/vehicle/vanishing_point.hpp"
#include "support/test_support.hpp"
#include "synthetic_camera.hpp"

using namespace mapfuse;
using namespace mapfuse::vehicle;

namespace {
constexpr double kExactTol = 1e-9;            // relative, noise-free back-projection
constexpr double kRangeErrorFraction = 0.02;  // acceptance: 2 % of range
constexpr double kDeg = M_PI / 180.0;
constexpr double kHeight = 1.55;
}  // namespace

TEST_CASE("eq. (1) inverts the projection of ground points exactly") {
  const Eigen::Matrix3d K = test::syntheticK();
  for (double pitch : {0.0, 2.0 * kDeg, -1.5 * kDeg}) {
    for (double roll : {0.0, 1.0 * kDeg}) {
      GroundPlane plane{tiltNormal(Eigen::Vector3d(0, -1, 0), pitch, roll), kHeight};
      for (double fwd = 5.0; fwd <= 30.0; fwd += 2.5)
        for (double left : {-5.25, -1.75, 1.75, 5.25}) {
          const Eigen::Vector3d X = test::groundPointCam(fwd, left, kHeight, pitch, roll);
          const auto px = projectPoint(K, X);
          REQUIRE(px);
          const auto Y = backProjectToGround(*px, K.inverse(), plane);
          REQUIRE(Y);
          CHECK((*Y - X).norm() <= kExactTol * X.norm());
        }
    }
  }
}

TEST_CASE("ranging rejects the sky and points outside the range band") {
  const Eigen::Matrix3d K = test::syntheticK();
  const GroundPlane plane{Eigen::Vector3d(0, -1, 0), kHeight};
  RangingSettings s;
  s.min_range = 5.0;
  s.max_range = 30.0;
  CHECK_FALSE(rangeGroundPixel({640, 100}, K, plane, s));  // above the horizon
  CHECK_FALSE(rangeGroundPixel({640, 360}, K, plane, s));  // the horizon itself
  const auto near = projectPoint(K, test::groundPointCam(3.0, 0, kHeight, 0, 0));
  const auto far = projectPoint(K, test::groundPointCam(45.0, 0, kHeight, 0, 0));
  const auto mid = projectPoint(K, test::groundPointCam(15.0, 0, kHeight, 0, 0));
  CHECK_FALSE(rangeGroundPixel(*near, K, plane, s));
  CHECK_FALSE(rangeGroundPixel(*far, K, plane, s));
  const auto g = rangeGroundPixel(*mid, K, plane, s);
  REQUIRE(g);
  // Covariance grows with range: the along-track variance dominates and is positive.
  const auto g2 =
      rangeGroundPixel(*projectPoint(K, test::groundPointCam(28.0, 0, kHeight, 0, 0)), K, plane, s);
  REQUIRE(g2);
  CHECK(g2->cov_cam(2, 2) > g->cov_cam(2, 2));
  CHECK(g->cov_cam.ldlt().isPositive());
}

TEST_CASE("ranging error stays within 2 % of range with 1 px noise and the true plane") {
  const Eigen::Matrix3d K = test::syntheticK();
  const GroundPlane plane{tiltNormal(Eigen::Vector3d(0, -1, 0), 1.0 * kDeg, 0.0), kHeight};
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 0.3);
  double worst = 0.0;
  for (double fwd = 5.0; fwd <= 30.0; fwd += 1.0) {
    const Eigen::Vector3d X = test::groundPointCam(fwd, 1.75, kHeight, 1.0 * kDeg, 0.0);
    Eigen::Vector2d px = *projectPoint(K, X);
    px += mapfuse::test::drawVector<Eigen::Vector2d>(noise, rng);
    const auto Y = backProjectToGround(px, K.inverse(), plane);
    REQUIRE(Y);
    worst = std::max(worst, (*Y - X).norm() / X.norm());
  }
  CHECK(worst <= kRangeErrorFraction);
}

namespace {
/// Pixels of straight lanes at the given lateral offsets, ranges 5-30 m.
std::vector<std::vector<Eigen::Vector2d>> lanePixels(double pitch, double roll, double yaw) {
  const Eigen::Matrix3d K = test::syntheticK();
  std::vector<std::vector<Eigen::Vector2d>> out;
  for (double left : {-5.25, -1.75, 1.75, 5.25}) {
    std::vector<Eigen::Vector2d> poly;
    for (double fwd = 5.0; fwd <= 30.0; fwd += 0.5) {
      // Lanes rotated by `yaw` in the road plane (vehicle not aligned with the lane).
      const double f = fwd * std::cos(yaw) - left * std::sin(yaw);
      const double l = fwd * std::sin(yaw) + left * std::cos(yaw);
      if (auto px = projectPoint(K, test::groundPointCam(f, l, kHeight, pitch, roll)))
        poly.push_back(*px);
    }
    out.push_back(poly);
  }
  return out;
}
}  // namespace

TEST_CASE("vanishing-point calibration reduces the error of a 1 degree pitch miscalibration 3x") {
  const Eigen::Matrix3d K = test::syntheticK();
  const double true_pitch = 1.0 * kDeg;  // camera mounted 1 degree off the nominal
  const GroundPlane nominal{Eigen::Vector3d(0, -1, 0), kHeight};
  for (double yaw : {0.0, 3.0 * kDeg}) {
    const auto lanes = lanePixels(true_pitch, 0.0, yaw);
    const auto corr = estimatePitchCorrection(lanes, K, nominal, VanishingSettings{});
    REQUIRE(corr);
    CHECK(*corr == Approx(true_pitch).margin(1e-6));
    const GroundPlane calibrated{tiltNormal(nominal.normal_cam, *corr, 0.0), kHeight};
    double err_nominal = 0.0, err_calibrated = 0.0;
    for (double fwd = 5.0; fwd <= 30.0; fwd += 1.0) {
      const Eigen::Vector3d X = test::groundPointCam(fwd, 1.75, kHeight, true_pitch, 0.0);
      const Eigen::Vector2d px = *projectPoint(K, X);
      err_nominal += (*backProjectToGround(px, K.inverse(), nominal) - X).norm() / X.norm();
      err_calibrated += (*backProjectToGround(px, K.inverse(), calibrated) - X).norm() / X.norm();
    }
    CHECK(err_calibrated * 3.0 <= err_nominal);
  }
}

TEST_CASE("two vanishing directions recover pitch and roll") {
  const double pitch = 1.2 * kDeg, roll = -0.8 * kDeg;
  const Eigen::Vector3d truth = tiltNormal(Eigen::Vector3d(0, -1, 0), pitch, roll);
  const Eigen::Vector3d d1 = test::tiltRotation(pitch, roll) * Eigen::Vector3d(0, 0, 1);
  const Eigen::Vector3d d2 = test::tiltRotation(pitch, roll) * Eigen::Vector3d(1, 0, 0.3);
  const auto n = normalFromTwoDirections(d1, d2, Eigen::Vector3d(0, -1, 0));
  REQUIRE(n);
  CHECK((*n - truth).norm() < 1e-9);
  CHECK_FALSE(normalFromTwoDirections(d1, d1, Eigen::Vector3d(0, -1, 0)));
}

TEST_CASE("curved or single lanes give no vanishing point, and smoothing takes the window median") {
  const Eigen::Matrix3d K = test::syntheticK();
  const GroundPlane nominal{Eigen::Vector3d(0, -1, 0), kHeight};
  auto lanes = lanePixels(0.0, 0.0, 0.0);
  lanes.resize(1);
  CHECK_FALSE(estimatePitchCorrection(lanes, K, nominal, VanishingSettings{}));
  const auto smooth = smoothCorrections({0.01, std::nullopt, 0.012, 0.5, 0.011}, 5);
  REQUIRE(smooth.size() == 5);
  CHECK(smooth[2] == Approx(0.012));
  CHECK(smooth[1] == Approx(0.012));  // median of {0.01, 0.012, 0.5}
}
