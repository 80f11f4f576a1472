// The vanishing-point ground calibration cannot hurt (issue 21): on curved roads its per-frame
// estimates are biased and the gate rejects them (or falls back to the static extrinsic); on a
// straight road it still recovers a known camera mount pitch error.
#include <Eigen/Geometry>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <random>

#include "mapfuse/vehicle/camera.hpp"
#include "mapfuse/vehicle/lsm_build.hpp"
#include "mapfuse/vehicle/vp_gate.hpp"
#include "support/test_support.hpp"
#include "synthetic_camera.hpp"

using namespace mapfuse;
using namespace mapfuse::vehicle;

namespace {
constexpr double kPitchTol = 0.0005;  // rad, recovered mount pitch / residual bias (0.36 px)
constexpr double kWindowTol = 0.001;  // rad, a frame's windowed median (fewer frames near ends)
constexpr double kHeight = 1.5;       // m, camera above the road
constexpr double kPixelNoise = 0.3;   // px, sigma of the synthetic lane pixels
constexpr double kStep = 0.1;         // m, road integration step

/// A road from its curvature profile: centre line, heading, per 0.1 m of arc length.
struct Road {
  std::vector<Eigen::Vector2d> centre;
  std::vector<double> heading;
  Eigen::Vector2d at(double s, double left) const {
    const std::size_t k = std::min(centre.size() - 1, std::size_t(std::max(0.0, s / kStep)));
    return centre[k] + left * Eigen::Vector2d(-std::sin(heading[k]), std::cos(heading[k]));
  }
  double headingAt(double s) const {
    return heading[std::min(heading.size() - 1, std::size_t(std::max(0.0, s / kStep)))];
  }
};

template <class Curvature>
Road makeRoad(double length, Curvature kappa) {
  Road r;
  Eigen::Vector2d p = Eigen::Vector2d::Zero();
  double th = 0.0;
  for (double s = 0.0; s <= length; s += kStep) {
    r.centre.push_back(p);
    r.heading.push_back(th);
    p += kStep * Eigen::Vector2d(std::cos(th), std::sin(th));
    th += kStep * kappa(s);
  }
  return r;
}

/// A drive at 1 m per frame along the road's centre, 4 lane lines (the middle two dashed 3 m /
/// 6 m), seen by a camera whose mount is pitched by `mount_pitch` against the nominal level one.
DriveData makeDrive(
    const Road& road, int frames, double mount_pitch,
    const std::vector<double>& lines = {-5.25, -1.75, 1.75, 5.25},
    const std::function<double(double)>& height = [](double) { return 0.0; }) {
  DriveData d;
  d.drive_id = "synthetic";
  d.calib.K = test::syntheticK();
  d.calib.width = 1280;
  d.calib.height = 720;
  Eigen::Matrix3d R_body_cam;  // camera x right, y down, z forward; body x forward, z up
  R_body_cam << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  d.calib.T_body_cam = Pose3::Identity();
  d.calib.T_body_cam.linear() = R_body_cam;
  d.calib.T_body_cam.translation() = Eigen::Vector3d(0, 0, kHeight);
  d.calib.ground = GroundPlane{Eigen::Vector3d(0, -1, 0), kHeight};
  const Eigen::Matrix3d R_true = test::tiltRotation(mount_pitch, 0.0);  // level cam -> true cam
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, kPixelNoise);
  for (int i = 0; i < frames; ++i) {
    const double s0 = double(i);
    Pose3 T = Pose3::Identity();
    const Eigen::Vector2d c = road.at(s0, 0.0);
    T.translation() = Eigen::Vector3d(c.x(), c.y(), height(s0));
    const double grade = (height(s0 + 0.5) - height(s0 - 0.5));  // per m
    T.linear() = (Eigen::AngleAxisd(road.headingAt(s0), Eigen::Vector3d::UnitZ()) *
                  Eigen::AngleAxisd(-std::atan(grade), Eigen::Vector3d::UnitY()))
                     .matrix();  // nose up on a climb
    d.T_odom_body.push_back(T);
    d.stamps.push_back(0.1 * i);
    FrameObservations f;
    f.index = i;
    f.stamp = 0.1 * i;
    const Pose3 T_cam_odom = (T * d.calib.T_body_cam).inverse();
    for (double left : lines) {
      const bool dashed = std::abs(left) < 2.0;
      GroundObservation g;
      for (double s = s0; s <= s0 + 40.0; s += 0.25) {
        if (dashed && std::fmod(s, 9.0) > 3.0) continue;
        const Eigen::Vector2d q = road.at(s, left);
        const Eigen::Vector3d X = R_true * (T_cam_odom * Eigen::Vector3d(q.x(), q.y(), height(s)));
        const auto px = projectPoint(d.calib.K, X, 0.5);
        if (!px || px->x() < 0 || px->x() >= 1280 || px->y() < 0 || px->y() >= 720) continue;
        g.pixels.push_back(*px + mapfuse::test::drawVector<Eigen::Vector2d>(noise, rng));
      }
      if (!g.pixels.empty()) f.ground.push_back(std::move(g));
    }
    d.frames.push_back(std::move(f));
  }
  return d;
}

/// The settings without the gate: every vanishing point counts (the behaviour before issue 21).
LsmBuildSettings ungated() {
  LsmBuildSettings s;
  s.vanishing.max_heading_change = 3.2;
  s.vanishing.max_azimuth_error = 3.2;
  s.vanishing.min_frames = 1;
  s.vanishing.min_significance = 0.0;
  return s;
}

double meanOf(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m += x / double(v.size());
  return m;
}
}  // namespace

TEST_CASE("VP gate: the look-ahead heading change and chord of an arc") {
  const double radius = 500.0;
  const Road road = makeRoad(200.0, [&](double) { return 1.0 / radius; });
  std::vector<Pose3> poses;
  for (int i = 0; i < 100; ++i) {
    Pose3 T = Pose3::Identity();
    const Eigen::Vector2d c = road.at(i, 0.0);
    T.translation() = Eigen::Vector3d(c.x(), c.y(), 0.0);
    T.linear() = Eigen::AngleAxisd(road.headingAt(i), Eigen::Vector3d::UnitZ()).matrix();
    poses.push_back(T);
  }
  const auto m = lookAheadMotion(poses, 25.0);
  REQUIRE(m[10].valid);
  CHECK_FALSE(m[90].valid);                                            // the drive ends within 25 m
  CHECK(m[10].heading_change == Approx(25.0 / radius).epsilon(0.05));  // arc angle
  CHECK(std::atan2(m[10].direction_body.y(), m[10].direction_body.x()) ==
        Approx(12.5 / radius).epsilon(0.05));  // the chord turns half as much
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  CHECK(azimuthDifference(Eigen::Vector3d::UnitX(), Eigen::Vector3d(1, 0.1, 0.3), up) ==
        Approx(std::atan(0.1)));
}

TEST_CASE("VP gate: a straight road recovers a known mount pitch error") {
  const Road road = makeRoad(500.0, [](double) { return 0.0; });
  for (double mount : {0.01, -0.006}) {
    const DriveData d = makeDrive(road, 400, mount);
    LsmBuildResult r;
    calibrateGroundPlanes(d, LsmBuildSettings{}, r);
    INFO("mount " << mount << ": median " << r.vp.median << " rad from " << r.vp.accepted
                  << " frames, spread " << r.vp.spread << ", " << r.vp.fallback_reason);
    CHECK_FALSE(r.vp.fallback);
    CHECK(r.vp.accepted >= 300);
    CHECK(std::abs(r.vp.median - mount) <= kPitchTol);
    CHECK(std::abs(meanOf(r.pitch_corrections) - mount) <= kPitchTol);
  }
}

TEST_CASE("VP gate: curves bias the vanishing points, and the gate rejects them") {
  // A wide road (the car in its leftmost lane, four lines to its right) on a 400 m curve: the
  // lane lines still pass the straightness test in the image, the image edge cuts the lines on
  // either side at different ranges, and without the gate the median is biased (about 0.4/R rad;
  // on a wide curved merge the issue saw +0.0024 rad).
  const std::vector<double> wide{-1.75, 1.75, 5.25, 8.75, 12.25};
  const Road curve = makeRoad(500.0, [](double) { return 1.0 / 400.0; });
  const DriveData d = makeDrive(curve, 400, 0.0, wide);
  LsmBuildResult before, after;
  calibrateGroundPlanes(d, ungated(), before);
  calibrateGroundPlanes(d, LsmBuildSettings{}, after);
  INFO("ungated median " << before.vp.median << " rad from " << before.vp.accepted
                         << " frames; gated " << after.vp.accepted << " frames, rejected "
                         << after.vp.rejected_curve << " curved, fallback "
                         << after.vp.fallback_reason);
  CHECK(std::abs(before.vp.median) > 2 * kPitchTol);  // the bias the gate exists for
  CHECK(after.vp.fallback);
  CHECK(after.vp.rejected_curve >= 300);
  for (double c : after.pitch_corrections) CHECK(c == 0.0);

  // Straight, then the same curve, with a mount error: the straight part calibrates, the curve
  // does not pull the correction.
  const double mount = 0.008;
  const Road mixed = makeRoad(600.0, [](double s) { return s < 250.0 ? 0.0 : 1.0 / 400.0; });
  const DriveData dm = makeDrive(mixed, 550, mount, wide);
  LsmBuildResult gated, all;
  calibrateGroundPlanes(dm, LsmBuildSettings{}, gated);
  calibrateGroundPlanes(dm, ungated(), all);
  INFO("mixed: gated median " << gated.vp.median << " rad from " << gated.vp.accepted
                              << " frames; ungated " << all.vp.median);
  CHECK_FALSE(gated.vp.fallback);
  CHECK(gated.vp.rejected_curve >= 250);
  CHECK(std::abs(gated.vp.median - mount) <= kPitchTol);
  for (double c : gated.pitch_corrections) CHECK(std::abs(c - mount) <= kWindowTol);
}

TEST_CASE("VP gate: a sag biases the vanishing points, and the gate rejects it") {
  // A straight road, level for 150 m, then down into a sag of 4 km radius for 400 m (the grade
  // turns by 0.1), then climbing evenly (esmini tunnels: grades turning by 0.07-0.1 within
  // 70 m; there 18 of 20 drives took a 0.016-0.020 rad correction from the sags). Ahead of the
  // car the lines rise out of the plane under it and vanish above its horizon.
  const double mount = 0.008;
  constexpr double kSag = 2.5e-4;  // 1/m, vertical curvature
  const auto height = [&](double s) {
    const double u = std::clamp(s - 150.0, 0.0, 400.0);
    return kSag * u * u / 2.0 + kSag * 400.0 * std::max(0.0, s - 550.0);
  };
  const Road road = makeRoad(700.0, [](double) { return 0.0; });
  const DriveData d = makeDrive(road, 650, mount, {-5.25, -1.75, 1.75, 5.25}, height);
  const auto motion = lookAheadMotion(d.T_odom_body, 25.0);
  CHECK(motion[50].pitch_change == Approx(0.0).margin(1e-9));            // level
  CHECK(motion[300].pitch_change == Approx(25.0 * kSag).epsilon(0.05));  // in the sag
  LsmBuildResult gated, all;
  LsmBuildSettings ungated_vertical;
  ungated_vertical.vanishing.max_pitch_change = 3.2;
  calibrateGroundPlanes(d, LsmBuildSettings{}, gated);
  calibrateGroundPlanes(d, ungated_vertical, all);
  INFO("gated median " << gated.vp.median << " rad from " << gated.vp.accepted << " frames ("
                       << gated.vp.rejected_vertical_curve << " in the sag); without the "
                       << "pitch gate " << all.vp.median << " rad from " << all.vp.accepted);
  CHECK(std::abs(all.vp.median - mount) > 2 * kPitchTol);  // the bias the gate exists for
  CHECK(gated.vp.rejected_vertical_curve >= 350);
  CHECK_FALSE(gated.vp.fallback);
  CHECK(std::abs(gated.vp.median - mount) <= kPitchTol);
}

TEST_CASE("VP gate: too few supporting frames keep the static extrinsic") {
  const Road road = makeRoad(200.0, [](double) { return 0.0; });
  const DriveData d = makeDrive(road, 60, 0.01);  // 35 frames with a full look-ahead
  LsmBuildResult r;
  calibrateGroundPlanes(d, LsmBuildSettings{}, r);
  CHECK(r.vp.fallback);
  CHECK(r.vp.fallback_reason == "too few frames");
  CHECK(r.vp.accepted < LsmBuildSettings{}.vanishing.min_frames);
  for (double c : r.pitch_corrections) CHECK(c == 0.0);
}
