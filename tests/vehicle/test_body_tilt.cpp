// vehicle::roadTiltInBody / tiltByBodyRotation / tiltedCameraHeight on hand-made motions whose
// answers are known: a body pitching and rolling on its suspension over a level road (box and
// Hann windows), a long climb (road grade, not tilt), the camera height on a pitched body, and
// bad inputs.
#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>

#include "mapfuse/core/error.hpp"
#include "vehicle/body_tilt.hpp"

using namespace mapfuse;

namespace {
constexpr double kRate = 10.0;        // Hz, camera frames
constexpr double kWindow = 2.0;       // s
constexpr double kOscillation = 0.7;  // Hz, suspension
constexpr double kAmplitude = 0.01;   // rad
constexpr double kHannLeak = 0.03;    // Hann 4 s: fraction of a 0.5-0.7 Hz oscillation left
constexpr double kHeightTol = 1e-9;   // m, camera height (the model is exact for this pivot)

Pose3 pose(double yaw, double pitch, double roll, const Eigen::Vector3d& t) {
  Pose3 T = Pose3::Identity();
  T.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  T.translation() = t;
  return T;
}

/// A slow turn over a level road at 8 m/s, `n` frames: the body pitches kAmplitude at
/// kOscillation and rolls half that at `roll_hz` (the suspension).
void suspensionDrive(int n, double roll_hz, std::vector<Pose3>& poses,
                     std::vector<double>& stamps) {
  for (int i = 0; i < n; ++i) {
    const double t = i / kRate;
    poses.push_back(pose(0.05 * t, kAmplitude * std::sin(2 * M_PI * kOscillation * t),
                         0.5 * kAmplitude * std::sin(2 * M_PI * roll_hz * t + 1.0),
                         Eigen::Vector3d(8.0 * t, 0.0, 0.0)));
    stamps.push_back(t);
  }
}

/// Angle between the tilt's image of e_z and the true road normal in the body frame.
double normalError(const Eigen::Matrix3d& tilt, const Pose3& T_odom_body,
                   const Eigen::Vector3d& road_odom) {
  const Eigen::Vector3d est = tilt * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d truth = T_odom_body.linear().transpose() * road_odom;
  return std::acos(std::clamp(est.dot(truth.normalized()), -1.0, 1.0));
}
}  // namespace

TEST_CASE("body tilt: suspension pitch and roll over a level road are followed") {
  // 20 s of driving in a slow turn; pitch and roll oscillate at 0.7 and 0.45 Hz.
  std::vector<Pose3> poses;
  std::vector<double> stamps;
  suspensionDrive(200, 0.45, poses, stamps);
  const auto tilt = vehicle::roadTiltInBody(poses, stamps, kWindow);
  REQUIRE(tilt.size() == poses.size());
  double worst = 0.0, worst_fixed = 0.0;
  for (std::size_t i = 20; i + 20 < poses.size(); ++i) {  // full windows
    worst = std::max(worst, normalError(tilt[i], poses[i], Eigen::Vector3d::UnitZ()));
    worst_fixed = std::max(
        worst_fixed, normalError(Eigen::Matrix3d::Identity(), poses[i], Eigen::Vector3d::UnitZ()));
  }
  INFO("worst normal error " << worst << " rad with the tilt, " << worst_fixed << " without");
  // The window average of a sinusoid over 1.4 of its periods leaves ~0.15 of the amplitude.
  CHECK(worst < 0.25 * kAmplitude);
  CHECK(worst_fixed > 0.9 * kAmplitude);
}

TEST_CASE("body tilt: a steady climb is road grade, not tilt, windows off, bad input") {
  // A 3 % grade driven at a constant pitch: the body lies on the road, nothing to correct.
  std::vector<Pose3> poses;
  std::vector<double> stamps;
  const double grade = std::atan(0.03);
  for (int i = 0; i < 100; ++i) {
    poses.push_back(pose(0.0, -grade, 0.0, Eigen::Vector3d(0.8 * i, 0.0, 0.024 * i)));
    stamps.push_back(i / kRate);
  }
  const auto tilt = vehicle::roadTiltInBody(poses, stamps, kWindow);
  for (const auto& R : tilt) CHECK((R - Eigen::Matrix3d::Identity()).norm() < 1e-9);
  for (const auto& R : vehicle::roadTiltInBody(poses, stamps, 0.0))
    CHECK(R == Eigen::Matrix3d::Identity());

  // The nominal camera normal is rotated by the body-frame tilt through the mount.
  const Eigen::Matrix3d R_body_cam =
      (Eigen::Matrix3d() << 0, 0, 1, -1, 0, 0, 0, -1, 0).finished();  // x right, y down, z ahead
  const Eigen::Vector3d n_cam = R_body_cam.transpose() * Eigen::Vector3d::UnitZ();
  const Eigen::Matrix3d pitch =
      Eigen::AngleAxisd(0.02, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Vector3d tilted = vehicle::tiltByBodyRotation(n_cam, pitch, R_body_cam);
  CHECK((R_body_cam * tilted - pitch * Eigen::Vector3d::UnitZ()).norm() < 1e-12);

  stamps.pop_back();
  CHECK_THROWS_AS(vehicle::roadTiltInBody(poses, stamps, kWindow), InputError);
  stamps.push_back(0.0);  // backwards
  CHECK_THROWS_AS(vehicle::roadTiltInBody(poses, stamps, kWindow), InputError);
}

TEST_CASE("body tilt: a Hann window leaves a fraction of the box window's oscillation") {
  // The simulator's suspension: pitch 0.01 rad at 0.7 Hz, roll 0.005 rad at 0.5 Hz, on a level
  // road in a slow turn. Transfer at f of a window of length W: box sin(pi f W)/(pi f W) (0.22 at
  // 0.7 Hz, 2 s), Hann sinc(f W)/(1 - (f W)^2) (0.010 at 0.7 Hz, 4 s; 0 at 0.5 Hz).
  std::vector<Pose3> poses;
  std::vector<double> stamps;
  suspensionDrive(300, 0.5, poses, stamps);
  auto worst = [&](double window, vehicle::TiltWeighting w) {
    const auto tilt = vehicle::roadTiltInBody(poses, stamps, window, w);
    double e = 0.0;
    for (std::size_t i = 30; i + 30 < poses.size(); ++i)  // full windows
      e = std::max(e, normalError(tilt[i], poses[i], Eigen::Vector3d::UnitZ()));
    return e;
  };
  const double box2 = worst(2.0, vehicle::TiltWeighting::kBox);
  const double hann4 = worst(4.0, vehicle::TiltWeighting::kHann);
  INFO("worst normal error: box 2 s " << box2 << " rad, Hann 4 s " << hann4 << " rad");
  CHECK(box2 > 0.15 * kAmplitude);
  CHECK(hann4 < kHannLeak * kAmplitude);
}

TEST_CASE("body tilt: the camera height follows a pitch about the body origin") {
  // The simulator's mount: camera 1.8 m ahead of and 1.4 m above the body origin, which lies on
  // the road. Pitching the body by p about its origin puts the camera at the height the pose
  // gives directly (independent reference: z of T_enu_body * t_body_cam).
  Pose3 T_body_cam = Pose3::Identity();
  T_body_cam.linear() = (Eigen::Matrix3d() << 0, 0, 1, -1, 0, 0, 0, -1, 0).finished();
  T_body_cam.translation() = Eigen::Vector3d(1.8, 0.0, 1.4);
  const Eigen::Vector3d n_cam = T_body_cam.linear().transpose() * Eigen::Vector3d::UnitZ();
  for (double p : {-0.02, -0.01, 0.005, 0.01, 0.02})
    for (double r : {-0.01, 0.0, 0.007}) {
      const Pose3 T_enu_body = pose(0.3, p, r, Eigen::Vector3d(5.0, -2.0, 0.0));
      const double truth = (T_enu_body * T_body_cam.translation()).z();
      // The tilt maps the body's up axis to the road normal seen from the body.
      const Eigen::Vector3d road_body = T_enu_body.linear().transpose() * Eigen::Vector3d::UnitZ();
      const Eigen::Matrix3d R_tilt =
          Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), road_body)
              .toRotationMatrix();
      const double h = vehicle::tiltedCameraHeight(1.4, n_cam, R_tilt, T_body_cam);
      INFO("pitch " << p << " roll " << r << ": height " << h << ", truth " << truth);
      CHECK(std::abs(h - truth) < kHeightTol);
      if (std::abs(p) >= 0.01) CHECK(std::abs(1.4 - truth) > 0.015);  // it matters: 1.8 m * p
    }
}
