// geo/track_agreement.hpp against constructed tracks whose disagreement is known exactly.
#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>

#include "mapfuse/geo/track_agreement.hpp"

using namespace mapfuse;

namespace {
constexpr double kTol = 1e-9;
/// A 1 km track: a straight 400 m, a quarter circle of 150 m radius, then straight on.
std::vector<Eigen::Vector3d> referenceTrack() {
  std::vector<Eigen::Vector3d> t;
  for (double s = 0; s <= 1000.0; s += 5.0) {
    Eigen::Vector3d p;
    if (s <= 400.0) {
      p = {s, 0.0, 0.0};
    } else if (s <= 400.0 + 150.0 * M_PI / 2) {
      const double a = (s - 400.0) / 150.0;
      p = {400.0 + 150.0 * std::sin(a), 150.0 * (1.0 - std::cos(a)), 0.0};
    } else {
      p = {550.0, 150.0 + (s - 400.0 - 150.0 * M_PI / 2), 0.0};
    }
    t.push_back(p);
  }
  return t;
}
}  // namespace

TEST_CASE("track agreement: a rotated, shifted copy agrees exactly") {
  const auto ref = referenceTrack();
  Pose3 T = Pose3::Identity();
  T.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(-30.0, 12.0, 4.0);
  std::vector<Eigen::Vector3d> odom;
  for (const auto& p : ref) odom.push_back(T * p);
  const geo::TrackAgreement a = geo::trackAgreement(odom, ref, geo::kScaleWindow);
  CHECK(a.samples == int(ref.size()));
  CHECK(a.horizontal_rms < 1e-6);
  CHECK(a.vertical_rms < kTol);
  CHECK(std::abs(a.vertical_slope) < kTol);
  CHECK(std::abs(a.scale_error) < 1e-9);
  CHECK(a.length == Approx(1000.0).epsilon(1e-3));
}

TEST_CASE("track agreement: a climbing, stretched odometry is measured per axis") {
  const auto ref = referenceTrack();
  constexpr double kStretch = 1.03;  // odometry 3 % long: a wheel scale error
  constexpr double kClimb = 0.01;    // odometry climbs 1 m per 100 m: a pitched IMU
  std::vector<Eigen::Vector3d> odom;
  double s = 0.0;
  for (std::size_t i = 0; i < ref.size(); ++i) {
    if (i > 0) s += (ref[i] - ref[i - 1]).norm() * kStretch;
    odom.push_back(Eigen::Vector3d(ref[i].x() * kStretch, ref[i].y() * kStretch, kClimb * s));
  }
  const geo::TrackAgreement a = geo::trackAgreement(odom, ref, geo::kScaleWindow);
  CHECK(a.scale_error == Approx(1.0 / kStretch - 1.0).margin(1e-3));
  CHECK(a.vertical_slope == Approx(-kClimb).margin(1e-6));  // reference minus odometry
  // a linear climb about its mean: RMS = slope * length / sqrt(12)
  CHECK(a.vertical_rms == Approx(kClimb * a.length / std::sqrt(12.0)).epsilon(0.02));
  CHECK(a.horizontal_rms > 1.0);  // a 3 % stretch cannot be fitted by a rotation
}

TEST_CASE("track agreement: empty and one-sample tracks give zeros") {
  CHECK(geo::trackAgreement({}, {}, geo::kScaleWindow).samples == 0);
  const geo::TrackAgreement one =
      geo::trackAgreement({Eigen::Vector3d(1, 2, 3)}, {Eigen::Vector3d(4, 5, 6)}, 200.0);
  CHECK(one.samples == 1);
  CHECK(one.horizontal_rms == Approx(0.0).margin(kTol));
  CHECK(one.scale_error == 0.0);
}
