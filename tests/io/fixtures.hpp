#pragma once
/// @file Small hand-made LSM and vector map used by the io tests, and the element comparison
/// of their round trips.
#include <catch2/catch.hpp>

#include "mapfuse/core/lsm.hpp"
#include "mapfuse/core/vector_map.hpp"

namespace mapfuse::test {

inline Lsm makeLsm() {
  Lsm lsm;
  lsm.drive_id = "drive_007";
  lsm.vehicle_id = "car_2";
  lsm.frame = LsmFrame::kEnu;
  lsm.origin = geo::GeoOrigin{49.0110, 8.4228, 112.8};
  for (int i = 0; i < 3; ++i) {
    Keyframe k;
    k.id = i;
    k.stamp = 0.5 * i;
    k.T_frame_body = poseFromXyzRpy(5.0 * i, 0.1 * i, 0.0, 0.0, 0.01, 0.02 * i);
    k.covariance = diagonalCovariance(0.05 * (i + 1), 0.002);
    lsm.keyframes.push_back(k);
  }
  lsm.keyframes[2].covariance(0, 1) = lsm.keyframes[2].covariance(1, 0) = 1e-4;  // non-diagonal
  lsm.gps.push_back({0.0, {49.0110, 8.4228, 113.0}, 1.5, 3.0});
  Element lane;
  lane.id = 10;
  lane.cls = CrowdClass::kLaneLine;
  lane.attributes = {LineStyle::kDashed, LineColor::kWhite};
  lane.anchor = 1;
  lane.points_body = {{2, 1.7, 0}, {3, 1.7, 0}, {4, 1.71, 0}};
  for (int i = 0; i < 3; ++i)
    lane.covariances.push_back(Eigen::Vector3d(0.01, 0.02, 0.03).asDiagonal());
  lane.confidence = 0.8;
  lane.observations = 5;
  lane.truth_id = 42;
  Element pole;
  pole.id = 11;
  pole.cls = CrowdClass::kPole;
  pole.anchor = 2;
  pole.points_body = {{8, -3, 0}};
  pole.covariances = {Eigen::Matrix3d::Identity() * 0.04};
  pole.height = 4.5;
  lsm.elements = {lane, pole};
  return lsm;
}

inline VectorMap makeVectorMap() {
  VectorMap map;
  map.origin = {49.0110, 8.4228, 112.8};
  map.source = "test";
  MapInstance lane;
  lane.id = 1;
  lane.cls = CrowdClass::kLaneLine;
  lane.attributes = {LineStyle::kSolid, LineColor::kYellow};
  lane.bezier = {BezierSegment{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(3, 0, 0),
                               Eigen::Vector3d(6, 1, 0), Eigen::Vector3d(9, 1, 0)}};
  lane.points = {{0, 0, 0}, {4.5, 0.5, 0}, {9, 1, 0}};
  lane.support = {12, 340};
  MapInstance sign;
  sign.id = 2;
  sign.cls = CrowdClass::kTrafficSign;
  sign.points = {{10, 5, 2}, {10, 5.6, 2}, {10, 5.6, 2.6}, {10, 5, 2.6}};
  sign.support = {3, 20};
  sign.source_ids = {7, 8};
  MapInstance pole;
  pole.id = 3;
  pole.cls = CrowdClass::kPole;
  pole.points = {{12, -4, 0}};
  pole.height = 5.0;
  pole.note = "placed by simulator";
  map.instances = {lane, sign, pole};
  return map;
}

/// @brief The LSM elements of `a` and `b` agree: ids, classes, attributes, anchors, scores, and
/// every point and covariance within `tolerance` (0: bit-exact).
inline void checkSameElements(const Lsm& a, const Lsm& b, double tolerance) {
  REQUIRE(a.elements.size() == b.elements.size());
  for (std::size_t i = 0; i < a.elements.size(); ++i) {
    const auto &x = a.elements[i], &y = b.elements[i];
    CHECK(x.id == y.id);
    CHECK(x.cls == y.cls);
    CHECK(x.attributes == y.attributes);
    CHECK(x.anchor == y.anchor);
    CHECK(x.confidence == y.confidence);
    CHECK(x.observations == y.observations);
    CHECK(x.height == y.height);
    CHECK(x.truth_id == y.truth_id);
    REQUIRE(x.points_body.size() == y.points_body.size());
    REQUIRE(x.covariances.size() == y.covariances.size());
    for (std::size_t k = 0; k < x.points_body.size(); ++k) {
      CHECK((x.points_body[k] - y.points_body[k]).norm() <= tolerance);
      CHECK((x.covariances[k] - y.covariances[k]).norm() <= tolerance);
    }
  }
}

}  // namespace mapfuse::test
