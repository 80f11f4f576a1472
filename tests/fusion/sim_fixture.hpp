#pragma once
// Small in-test world for georef / align tests: a 300 m two-lane road with lane lines, stop
// lines, signs and poles; traversals with odometry drift, per-traversal GPS bias, white noise
// and multipath outliers; elements observed relative to the TRUE body pose and anchored to the
// nearest keyframe (so all of an element's error comes from its keyframe pose).
#include <cmath>
#include <random>
#include <vector>

#include "mapfuse/core/lsm.hpp"
#include "mapfuse/geo/origin.hpp"

namespace mapfuse::test {

struct TrueElement {
  int64_t id;
  CrowdClass cls;
  std::vector<Eigen::Vector3d> points;  // ENU
};

struct Traversal {
  Lsm lsm;                   // odom frame, as uploaded
  std::vector<Pose3> truth;  // T_enu_body per keyframe
  Eigen::Vector3d gps_bias;  // m
  int outliers = 0;          // injected multipath fixes
};

struct FixtureOptions {
  int traversals = 6;
  double road_offset_y = 0.0;  // shifts the whole road (to build disjoint roads)
  double gps_bias = 2.0;       // m, magnitude of the per-traversal bias
  double gps_white = 0.3;      // m
  double outlier_probability = 0.05;
  double yaw_drift = 0.0015;  // rad per keyframe, random-walk sigma
  double scale_error = 0.01;  // odometry scale error sigma
  uint64_t seed = 1;
};

inline geo::GeoOrigin fixtureOrigin() {
  return {49.0, 8.4, 110.0};
}

inline std::vector<TrueElement> trueWorld(double y0 = 0.0) {
  std::vector<TrueElement> w;
  int64_t id = 0;
  for (double y : {-3.5, 0.0, 3.5}) {  // three lane lines, sampled every 0.5 m in 10 m pieces
    for (double x0 = 0; x0 < 300; x0 += 10) {
      TrueElement e{id++, CrowdClass::kLaneLine, {}};
      for (double x = x0; x <= x0 + 10.0 + 1e-9; x += 0.5)
        e.points.emplace_back(x, y0 + y + 2.0 * std::sin(x / 60.0), 0.0);
      w.push_back(e);
    }
  }
  for (double x : {60.0, 150.0, 240.0}) {  // stop lines across the right lane
    TrueElement e{id++, CrowdClass::kStopLine, {}};
    const double yc = y0 + 2.0 * std::sin(x / 60.0);
    for (double y = -3.5; y <= 0.0 + 1e-9; y += 0.25) e.points.emplace_back(x, yc + y, 0.0);
    w.push_back(e);
  }
  for (double x = 15; x < 300; x += 25) {  // poles on both sides, signs on the right
    for (double side : {-7.0, 7.0}) {
      TrueElement p{id++, CrowdClass::kPole, {}};
      p.points.emplace_back(x, y0 + side + 2.0 * std::sin(x / 60.0), 0.0);
      w.push_back(p);
    }
    TrueElement s{id++, CrowdClass::kTrafficSign, {}};
    const double ys = y0 - 7.0 + 2.0 * std::sin(x / 60.0);
    for (double dy : {-0.4, 0.4})
      for (double z : {2.0, 2.8}) s.points.emplace_back(x + 0.3, ys + dy, z);
    w.push_back(s);
  }
  return w;
}

inline Traversal makeTraversal(const std::vector<TrueElement>& world, int index,
                               const FixtureOptions& o) {
  std::mt19937_64 rng(o.seed * 1000 + index);
  std::normal_distribution<double> n01(0.0, 1.0);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  // Three draws, z first, then y, then x: the order gcc gave `Vector3d(n01(rng), n01(rng),
  // n01(rng))` (unsequenced arguments; clang draws x first), so the fixture is the same world
  // under both compilers.
  auto normal3 = [&] {
    const double z = n01(rng), y = n01(rng), x = n01(rng);
    return Eigen::Vector3d(x, y, z);
  };
  const geo::EnuConverter enu(fixtureOrigin());
  Traversal tr;
  Lsm& lsm = tr.lsm;
  lsm.drive_id = "trav" + std::to_string(index);
  lsm.vehicle_id = "veh" + std::to_string(index % 3);
  const double lane_y = -1.75 + 0.3 * n01(rng), speed = 10.0, spacing = 8.0;
  // true trajectory along the road centre curve
  auto trueAt = [&](double x) {
    const double y = o.road_offset_y + lane_y + 2.0 * std::sin(x / 60.0);
    const double yaw = std::atan(2.0 / 60.0 * std::cos(x / 60.0));
    return poseFromXyzRpy(x, y, 0.0, 0.0, 0.0, yaw);
  };
  const double scale = 1.0 + o.scale_error * n01(rng);
  double yaw_err = 0.0;
  Pose3 odom = Pose3::Identity();
  int64_t kid = 0;
  for (double x = 2.0; x <= 298.0; x += spacing) {
    const Pose3 T = trueAt(x);
    if (!tr.truth.empty()) {
      Pose3 rel = tr.truth.back().inverse() * T;
      rel.translation() *= scale;
      yaw_err += o.yaw_drift * n01(rng);
      rel = rel * poseFromXyzRpy(0, 0, 0, 0, 0, yaw_err * 0.1);
      odom = odom * rel;
    }
    tr.truth.push_back(T);
    Keyframe k;
    k.id = kid++;
    k.stamp = x / speed;
    k.T_frame_body = odom;
    k.covariance = diagonalCovariance(0.01 + 0.01 * x, 0.001 + 0.0005 * x);
    lsm.keyframes.push_back(k);
  }
  const double a = 2 * M_PI * u01(rng);
  tr.gps_bias = o.gps_bias * Eigen::Vector3d(std::cos(a), std::sin(a), 0.3 * n01(rng));
  for (double t = lsm.keyframes.front().stamp; t <= lsm.keyframes.back().stamp; t += 1.0) {
    Eigen::Vector3d p = trueAt(t * speed).translation() + tr.gps_bias + o.gps_white * normal3();
    if (u01(rng) < o.outlier_probability) {
      const double b = 2 * M_PI * u01(rng);
      p += (10.0 + 10.0 * u01(rng)) * Eigen::Vector3d(std::cos(b), std::sin(b), 0.0);
      ++tr.outliers;
    }
    GpsFix f;
    f.stamp = t;
    f.position = enu.toWgs84(p);
    f.sigma_h = 2.5;
    f.sigma_v = 4.0;
    lsm.gps.push_back(f);
  }
  // elements, anchored to the keyframe nearest their first point
  int64_t eid = 0;
  for (const auto& te : world) {
    const Eigen::Vector3d c = te.points.front();
    if (std::abs(c.y() - tr.truth.front().translation().y()) > 30.0) continue;  // other road
    int best = 0;
    for (int k = 0; k < int(tr.truth.size()); ++k)
      if ((tr.truth[k].translation() - c).norm() < (tr.truth[best].translation() - c).norm())
        best = k;
    if ((tr.truth[best].translation() - c).norm() > 25.0) continue;
    Element e;
    e.id = eid++;
    e.cls = te.cls;
    e.anchor = lsm.keyframes[best].id;
    e.truth_id = te.id;
    if (te.cls == CrowdClass::kPole) e.height = 5.0;
    for (const auto& p : te.points) {
      const Eigen::Vector3d n = normal3();
      e.points_body.push_back(tr.truth[best].inverse() * p +
                              0.03 * Eigen::Vector3d(n.x(), n.y(), 0.3 * n.z()));
      e.covariances.push_back(Eigen::Matrix3d::Identity() * 0.03 * 0.03);
    }
    lsm.elements.push_back(e);
  }
  return tr;
}

}  // namespace mapfuse::test
