// Building blocks of the LiDAR odometry against brute force, constructed scenes and the
// definitions they implement: the bounded local voxel map, scan normals, the geometric split of
// a scan, SE(3) helpers and the step verdict.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "lidar/scan_normals.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/lidar/local_voxel_map.hpp"
#include "mapfuse/lidar/odometry_trust.hpp"
#include "mapfuse/lidar/scan_geometry.hpp"
#include "mapfuse/lidar/scan_odometry.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;

namespace {
constexpr double kExact = 1e-12;        // same arithmetic, reordered
constexpr double kOrthonormal = 1e-12;  // |R^T R - I| of a re-orthonormalised rotation

std::vector<Eigen::Vector3d> randomPoints(std::size_t n, double extent, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-extent, extent);
  std::vector<Eigen::Vector3d> pts(n);
  for (auto& p : pts) p = mapfuse::test::drawVector<Eigen::Vector3d>(u, rng);
  return pts;
}
}  // namespace

TEST_CASE("local voxel map: nearest neighbour equals brute force within one voxel",
          "[lidar][odometry]") {
  lidar::LocalVoxelMap map({1.0, 255, 1000.0});
  const auto pts = randomPoints(3000, 10.0, 1);
  map.update(pts, std::vector<Eigen::Vector3d>(pts.size(), Eigen::Vector3d::UnitZ()),
             Eigen::Vector3d::Zero());
  const auto stored = map.points();  // crowded points (closer than 1/sqrt(255) m) are not added
  REQUIRE(stored.size() > 2500);
  const auto queries = randomPoints(500, 10.0, 2);
  for (const auto& q : queries) {
    double best = 1.0;  // squared radius of exactness: one voxel edge
    for (const auto& p : stored) best = std::min(best, (p - q).squaredNorm());
    lidar::MapNeighbor nb;
    const bool found = map.nearest(q, 1.0, &nb);
    CHECK(found == (best < 1.0));
    if (found) {
      CHECK(std::abs(nb.dist_sq - best) < kExact);
      CHECK((nb.normal - Eigen::Vector3d::UnitZ()).norm() < kExact);
    }
  }
}

TEST_CASE("local voxel map: bounded by points per voxel and by distance from the sensor",
          "[lidar][odometry]") {
  lidar::LocalVoxelMap map({1.0, 5, 20.0});
  // 8 points in one voxel, 0.5 m apart (more than the 1/sqrt(5) m spacing): 5 are kept.
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i < 8; ++i)
    pts.emplace_back(0.2 + 0.5 * (i & 1), 0.2 + 0.5 * (i >> 1 & 1), 0.2 + 0.5 * (i >> 2));
  map.update(pts, std::vector<Eigen::Vector3d>(pts.size(), Eigen::Vector3d::Zero()),
             Eigen::Vector3d::Zero());
  CHECK(map.numVoxels() == 1);
  CHECK(map.numPoints() == 5);
  // The sensor moves 30 m away: the voxel is farther than max_distance and goes.
  map.update({{30.5, 0.5, 0.5}}, {Eigen::Vector3d::Zero()}, Eigen::Vector3d(30, 0, 0));
  CHECK(map.numVoxels() == 1);
  lidar::MapNeighbor nb;
  CHECK_FALSE(map.nearest(Eigen::Vector3d(0.5, 0.5, 0.5), 1.0, &nb));
  CHECK(map.nearest(Eigen::Vector3d(30.4, 0.5, 0.5), 1.0, &nb));
  CHECK_THROWS_AS(map.update(pts, std::vector<Eigen::Vector3d>{}, Eigen::Vector3d::Zero()),
                  InputError);
  CHECK_THROWS_AS(lidar::LocalVoxelMap({0.0, 5, 20.0}), ConfigError);
}

TEST_CASE("scan normals: planes get their normal, a single ring gets none", "[lidar][odometry]") {
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j) pts.emplace_back(0.25 * i, 0.25 * j, 0.01 * i);  // tilted plane
  const std::size_t plane = pts.size();
  for (int i = 0; i < 40; ++i) pts.emplace_back(50.0 + 0.25 * i, 0.0, 0.0);  // a line far away
  const auto n = lidar::estimateNormals(pts, 10, 1.0);
  const Eigen::Vector3d truth = Eigen::Vector3d(-0.04, 0, 1).normalized();  // z = 0.04 x
  for (std::size_t i = 0; i < plane; ++i) CHECK(std::abs(n[i].dot(truth)) > 1 - 1e-9);
  for (std::size_t i = plane; i < pts.size(); ++i) CHECK(n[i].norm() == 0.0);
  CHECK_THROWS_AS(lidar::estimateNormals(pts, 2, 1.0), InputError);
}

TEST_CASE("scan geometry: ground, a car, a truck under a bridge, a wall and a pole",
          "[lidar][odometry]") {
  // Sensor frame: ground at z = -1.73 sloping up 10 % in y (still ground), objects on it.
  std::vector<Eigen::Vector3d> pts;
  std::vector<lidar::ScanPointKind> truth;
  auto ground = [](double y) { return -1.73 + 0.1 * std::max(0.0, y - 10.0); };
  auto add = [&](double x, double y, double h, lidar::ScanPointKind k) {
    pts.emplace_back(x, y, ground(y) + h);
    truth.push_back(k);
  };
  using K = lidar::ScanPointKind;
  for (double x = -30; x <= 30; x += 0.5)
    for (double y = -30; y <= 30; y += 0.5) add(x, y, 0.0, K::kGround);
  for (double x = 8; x <= 12.5; x += 0.2)  // car, 1.5 m high
    for (double z = 0.4; z <= 1.5; z += 0.2) add(x, -4.0, z, K::kRoadUser);
  for (double x = -20; x <= -8; x += 0.2)  // truck 3.8 m, bridge deck from 5.0 m above it
    for (double z = 0.5; z <= 3.8; z += 0.2) add(x, 4.0, z, K::kRoadUser);
  for (double x = -20; x <= -8; x += 0.2)
    for (double z = 5.0; z <= 6.0; z += 0.2) add(x, 4.0, z, K::kStatic);
  for (double x = -25; x <= 25; x += 0.2)  // building wall 8 m high
    for (double z = 0.0; z <= 8.0; z += 0.2) add(x, -20.0, z + 0.35, K::kStatic);
  for (double z = 0.4; z <= 7.0; z += 0.1) add(20.0, 6.0, z, K::kStatic);  // pole
  lidar::SceneGeometryStats st;
  const auto kinds = lidar::splitScanGeometry(pts, lidar::SceneGeometrySettings{}, &st);
  std::size_t wrong = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) wrong += kinds[i] != truth[i];
  CHECK(wrong == 0);
  CHECK(st.ground + st.static_points + st.road_user == pts.size());
  lidar::SceneGeometrySettings bad;
  bad.max_gap = 0;
  CHECK_THROWS_WITH(lidar::splitScanGeometry(pts, bad), Catch::Contains("max_gap"));
}

TEST_CASE("SE(3) helpers: orthonormalised rotations and scaled constant-velocity motion",
          "[lidar][odometry]") {
  Pose3 T = poseFromXyzRpy(1, 2, 3, 0.1, -0.2, 0.3);
  T.linear() *= 1.001;  // drifted off SO(3)
  T.linear()(0, 1) += 1e-3;
  const Pose3 R = lidar::orthonormalized(T);
  CHECK((R.linear().transpose() * R.linear() - Eigen::Matrix3d::Identity()).norm() < kOrthonormal);
  CHECK(R.linear().determinant() == Approx(1.0).epsilon(1e-12));
  CHECK((R.translation() - T.translation()).norm() == 0.0);
  const Pose3 step = poseFromXyzRpy(0.8, 0.05, 0.0, 0.0, 0.0, 0.02);
  const Pose3 two = lidar::scaleMotion(step, 2.0);
  CHECK(((step * step).matrix() - two.matrix()).cwiseAbs().maxCoeff() < 1e-12);
  CHECK((lidar::scaleMotion(step, 0.0).matrix() - Eigen::Matrix4d::Identity()).norm() < 1e-15);
}

TEST_CASE("step verdict: each check names its figure, a sound step is trusted",
          "[lidar][odometry]") {
  const lidar::TrustSettings s;
  lidar::MapRegistrationResult reg;
  reg.converged = true;
  reg.inlier_share = 0.9;
  const Pose3 prev = Pose3::Identity();
  Pose3 pred = Pose3::Identity();
  pred.translation().x() = 1.0;  // 10 m/s over 0.1 s
  reg.T_map_scan = pred;
  reg.T_map_scan.translation().x() = 1.02;
  auto a = lidar::assessStep(reg, prev, &pred, 0.1, 0.1, s);
  CHECK(a.trusted);
  CHECK(a.speed == Approx(10.2));
  CHECK(a.deviation_m == Approx(0.02));
  reg.inlier_share = 0.3;
  a = lidar::assessStep(reg, prev, &pred, 0.1, 0.1, s);
  CHECK_FALSE(a.trusted);
  CHECK_THAT(a.reasons, Catch::Contains("inlier share 0.30 < 0.50"));
  reg.inlier_share = 0.9;
  reg.T_map_scan.translation().x() = 5.0;  // 50 m/s, 4 m off the prediction
  a = lidar::assessStep(reg, prev, &pred, 0.1, 0.1, s);
  CHECK_THAT(a.reasons, Catch::Contains("speed 50.0 m/s"));
  CHECK_THAT(a.reasons, Catch::Contains("from the constant-velocity prediction"));
  a = lidar::assessStep(reg, prev, &pred, 0.1, 0.001, s);
  CHECK_THAT(a.reasons, Catch::Contains("degenerate"));
  reg.T_map_scan.translation().x() = 1.5;
  a = lidar::assessStep(reg, prev, nullptr, 0.1, 0.1, s);  // velocity unknown: no deviation
  CHECK(a.trusted);
  reg.converged = false;
  a = lidar::assessStep(reg, prev, nullptr, 0.1, 0.1, s);
  CHECK_THAT(a.reasons, Catch::Contains("did not converge"));
}

TEST_CASE("odometry settings: a bad value of each struct is a ConfigError naming owner and key",
          "[lidar][odometry]") {
  CHECK_NOTHROW(lidar::ScanOdometry(lidar::OdometrySettings{}));  // the defaults are valid
  struct Case {
    const char* message;
    void (*spoil)(lidar::OdometrySettings&);
  };
  const Case cases[] = {
      {"OdometrySettings::max_range", [](lidar::OdometrySettings& s) { s.max_range = 2.0; }},
      {"OdometrySettings::source_spacing",
       [](lidar::OdometrySettings& s) { s.source_spacing = 0.25; }},
      {"OdometrySettings::registration.max_iterations",
       [](lidar::OdometrySettings& s) { s.registration.max_iterations = 0; }},
      {"SceneGeometrySettings::ground_window",
       [](lidar::OdometrySettings& s) { s.geometry.ground_window = 51; }},
      {"TrustSettings::min_inlier_share",
       [](lidar::OdometrySettings& s) { s.trust.min_inlier_share = 1.5; }},
      {"TrustSettings::max_speed",
       [](lidar::OdometrySettings& s) { s.trust.max_speed = std::nan(""); }},
  };
  for (const Case& c : cases) {
    INFO(c.message);
    lidar::OdometrySettings s;
    c.spoil(s);
    CHECK_THROWS_AS(lidar::ScanOdometry(s), ConfigError);  // exit 2
    CHECK_THROWS_WITH(lidar::ScanOdometry(s), Catch::Contains(c.message));
  }
}
