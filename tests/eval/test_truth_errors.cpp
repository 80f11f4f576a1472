// eval::elementTruthErrors / trajectoryTruthErrors on hand-made LSMs whose errors are known.
#include <catch2/catch.hpp>

#include "mapfuse/core/error.hpp"
#include "mapfuse/eval/truth_errors.hpp"
#include "mapfuse/geo/origin.hpp"

using namespace mapfuse;

namespace {
constexpr double kExact = 1e-9;   // m: sums of hand-picked offsets
constexpr double kGeoTol = 1e-3;  // m: an ENU frame 100 m away is rotated by ~1.6e-5 rad
const geo::GeoOrigin kOrigin{49.0, 8.4, 110.0};

MapInstance pole(int64_t id, double x, double y) {
  MapInstance m;
  m.id = id;
  m.cls = CrowdClass::kPole;
  m.points = {Eigen::Vector3d(x, y, 0.0)};
  return m;
}

// One keyframe at the identity, poles observed with a shift of `dx` m east.
Lsm drive(const std::string& id, double dx) {
  Lsm l;
  l.drive_id = id;
  l.frame = LsmFrame::kEnu;
  l.origin = kOrigin;
  l.keyframes.push_back(Keyframe{});
  for (auto [tid, x, y] : {std::tuple{1, 10.0, 0.0}, std::tuple{2, 30.0, 5.0}}) {
    Element e;
    e.id = tid;
    e.cls = CrowdClass::kPole;
    e.truth_id = tid;
    e.points_body = {Eigen::Vector3d(x + dx, y, 0.0)};
    e.covariances = {Eigen::Matrix3d::Identity() * 0.01};
    l.elements.push_back(e);
  }
  return l;
}
}  // namespace

TEST_CASE("truth errors: element spread, absolute error and common offset of known shifts",
          "[eval][truth]") {
  VectorMap truth;
  truth.origin = kOrigin;
  truth.instances = {pole(1, 10.0, 0.0), pole(2, 30.0, 5.0)};
  // Drive a sees both poles 0.3 m east, drive b 0.1 m west.
  const auto e = eval::elementTruthErrors({drive("a", 0.3), drive("b", -0.1)}, truth);
  CHECK(e.observations == 4);
  CHECK(e.groups == 2);
  CHECK(e.mean_abs == Approx(0.2).margin(kExact));  // (0.3 + 0.3 + 0.1 + 0.1) / 4
  CHECK(e.spread == Approx(0.2).margin(kExact));    // offsets 0.3, -0.1 about their mean 0.1
  CHECK(e.spread_median == Approx(0.2).margin(kExact));
  CHECK(e.mean_offset == Approx(0.1).margin(kExact));

  Lsm odom = drive("c", 0.0);
  odom.frame = LsmFrame::kOdom;
  CHECK_THROWS_AS(eval::elementTruthErrors({odom}, truth), InputError);
}

TEST_CASE("truth errors: a line seen in part is compared with the line, not its centroid",
          "[eval][truth]") {
  // A 15 m lane line (shorter than a 20 m piece) and a 6 m stop line along East; each drive
  // sees only the first 5 m of the lane line and 2 m of the stop line, shifted 0.2 m north
  // (drive a) or 0.2 m south (drive b). Their centroids differ from the true ones by ~5 m and
  // ~2 m along the lines; the errors are the 0.2 m shifts.
  VectorMap truth;
  truth.origin = kOrigin;
  MapInstance lane;
  lane.id = 7;
  lane.cls = CrowdClass::kLaneLine;
  lane.points = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(7.5, 0, 0), Eigen::Vector3d(15, 0, 0)};
  MapInstance stop = lane;
  stop.id = 8;
  stop.cls = CrowdClass::kStopLine;
  stop.points = {Eigen::Vector3d(0, 10, 0), Eigen::Vector3d(6, 10, 0)};
  truth.instances = {lane, stop};
  auto seen = [](const std::string& id, double dy) {
    Lsm l = drive(id, 0.0);
    l.elements.clear();
    for (const auto& [tid, cls, y0, x1] : {std::tuple{7, CrowdClass::kLaneLine, 0.0, 5.0},
                                           std::tuple{8, CrowdClass::kStopLine, 10.0, 2.0}}) {
      Element e;
      e.id = tid;
      e.cls = cls;
      e.truth_id = tid;
      for (double x = 0.0; x <= x1 + 1e-9; x += 0.5) {
        e.points_body.push_back(Eigen::Vector3d(x, y0 + dy, 0.0));
        e.covariances.push_back(Eigen::Matrix3d::Identity() * 0.01);
      }
      l.elements.push_back(e);
    }
    return l;
  };
  const auto e = eval::elementTruthErrors({seen("a", 0.2), seen("b", -0.2)}, truth);
  CHECK(e.observations == 4);
  CHECK(e.groups == 2);
  CHECK(e.mean_abs == Approx(0.2).margin(kExact));
  CHECK(e.spread == Approx(0.2).margin(kExact));
  CHECK(e.mean_offset == Approx(0.0).margin(kExact));
}

TEST_CASE("truth errors: keyframe ATE with a true trajectory in another ENU origin",
          "[eval][truth]") {
  // The LSM's keyframes every 10 m along East; the truth, in an origin ~100 m away, holds the
  // same points shifted 0.5 m south.
  const geo::GeoOrigin truth_origin{49.0009, 8.4, 110.0};
  const geo::EnuConverter lsm_enu(kOrigin), truth_enu(truth_origin);
  Lsm l = drive("a", 0.0);
  l.keyframes.clear();
  eval::TrueTrajectory t;
  t.drive_id = "a";
  t.origin = truth_origin;
  // Keyframes are matched by stamp, not id (lsm-build numbers its own keyframes): ids here are
  // offset by 100, and keyframe 4 lies halfway between the true poses at 4 s and 5 s.
  for (int k = 0; k < 6; ++k) {
    eval::TruePose p;
    p.id = k;
    p.stamp = double(k);
    p.T_enu_body.translation() =
        truth_enu.toEnu(lsm_enu.toWgs84(Eigen::Vector3d(10.0 * k, -0.5, 0.0)));
    t.poses.push_back(p);
  }
  for (int k = 0; k < 5; ++k) {
    Keyframe kf;
    kf.id = 100 + k;
    kf.stamp = k < 4 ? double(k) : 4.5;
    kf.T_frame_body.translation() = Eigen::Vector3d(10.0 * kf.stamp, 0.0, 0.0);
    l.keyframes.push_back(kf);
  }
  const auto r = eval::trajectoryTruthErrors({l}, {{"a", t}});
  CHECK(r.drives == 1);
  CHECK(r.ate_mean == Approx(0.5).margin(kGeoTol));
  CHECK(r.ate_max == Approx(0.5).margin(kGeoTol));
  CHECK(r.bias_mean == Approx(0.5).margin(kGeoTol));
}
