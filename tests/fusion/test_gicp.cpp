// GICP core: voxel hash, downsampling, covariances, registration against known transforms on a
// synthetic structured scene and on real KITTI odometry scans.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <random>

#include "mapfuse/core/error.hpp"
#include "mapfuse/fusion/gicp.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;
using namespace mapfuse::fusion;

namespace {
constexpr double kDeg = M_PI / 180.0;
// small_gicp's registration tolerance is 2.5 deg / 0.2 m; we hold ours much tighter.
constexpr double kSyntheticTransTol = 0.01;  // m
constexpr double kSyntheticRotTol = 0.05 * kDeg;
constexpr double kRealTransTol = 0.05;  // m, a real scan against its transformed, re-voxelised self
constexpr double kRealRotTol = 0.2 * kDeg;
constexpr double kCycleTransTol = 0.05;  // m, T01 * T12 vs T02 on consecutive real scans
constexpr double kCycleRotTol = 0.2 * kDeg;

double rotErr(const Pose3& a, const Pose3& b) {
  return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle();
}
double transErr(const Pose3& a, const Pose3& b) {
  return (a.translation() - b.translation()).norm();
}

// A street-like scene: ground, two building facades with windows recesses, poles, a car box.
Cloud structuredScene(uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.01);
  Cloud c;
  auto add = [&](const Eigen::Vector3d& p, uint8_t label) {
    c.points.push_back(p + mapfuse::test::drawVector<Eigen::Vector3d>(noise, rng));
    c.labels.push_back(label);
  };
  for (int i = 0; i < 20000; ++i) add({-30 + 60 * u(rng), -10 + 20 * u(rng), 0.0}, 1);
  for (int i = 0; i < 8000; ++i) {
    const double x = -30 + 60 * u(rng), z = 8 * u(rng);
    const double recess = (std::fmod(x + 30, 4.0) < 1.5 && z > 2 && z < 4) ? 0.3 : 0.0;
    add({x, 10 + recess, z}, 3);
    add({x, -10 - 0.5 * std::sin(0.3 * x), z}, 3);
  }
  for (int p = 0; p < 8; ++p)
    for (int i = 0; i < 300; ++i) {
      const double a = 2 * M_PI * u(rng);
      add({-25 + 7 * p + 0.1 * std::cos(a), -6 + 0.1 * std::sin(a), 6 * u(rng)}, 5);
    }
  for (int i = 0; i < 3000; ++i) add({3 + 4 * u(rng), 2 + 1.8 * u(rng), 1.5 * u(rng)}, 7);
  return c;
}

Cloud loadKittiScan(const std::filesystem::path& path) {
  std::ifstream f(path, std::ios::binary);
  REQUIRE(f.good());
  std::vector<float> raw;
  float v[4];
  while (f.read(reinterpret_cast<char*>(v), sizeof(v))) raw.insert(raw.end(), v, v + 4);
  Cloud c;
  for (std::size_t i = 0; i + 3 < raw.size(); i += 4)
    c.points.emplace_back(raw[i], raw[i + 1], raw[i + 2]);
  return c;
}

Cloud prepare(const Cloud& raw, double voxel) {
  Cloud c = voxelDownsample(raw, voxel);
  estimateCovariances(c, 10, 1.0);
  return c;
}
}  // namespace

TEST_CASE("voxel index finds the same nearest neighbour as brute force") {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-5.0, 5.0);
  std::vector<Eigen::Vector3d> pts(3000);
  for (auto& p : pts) p = {u(rng), u(rng), u(rng)};
  const VoxelIndex index(pts, 1.0);
  for (int q = 0; q < 200; ++q) {
    const Eigen::Vector3d x(u(rng), u(rng), u(rng));
    int best = -1;
    double bd = 1.0;
    for (int i = 0; i < int(pts.size()); ++i)
      if ((pts[i] - x).squaredNorm() < bd) bd = (pts[(best = i)] - x).squaredNorm();
    double d2 = -1;
    REQUIRE(index.nearest(x, 1.0, &d2) == best);
    if (best >= 0) CHECK(d2 == Approx(bd));
    int idx[5];
    double dd[5];
    const int k = index.knn(x, 5, idx, dd);
    REQUIRE(k == 5);  // 3000 points in 1000 m^3: always >= 5 within the 27 cells
    for (int i = 1; i < k; ++i) CHECK(dd[i - 1] <= dd[i]);
    if (best >= 0) CHECK(idx[0] == best);
    // Radius visits: exactly the points nearer than the radius, each once.
    const double r2 = 0.6 * 0.6;
    std::vector<int> visited, expected;
    index.forEachWithin(x, r2, [&](int i, double d) {
      visited.push_back(i);
      CHECK(d == Approx((pts[i] - x).squaredNorm()));
    });
    for (int i = 0; i < int(pts.size()); ++i)
      if ((pts[i] - x).squaredNorm() < r2) expected.push_back(i);
    std::sort(visited.begin(), visited.end());
    CHECK(visited == expected);
  }
}

TEST_CASE("voxel downsampling keeps centroids and majority labels") {
  Cloud c;
  c.points = {{0.1, 0.1, 0.1}, {0.3, 0.3, 0.3}, {0.2, 0.2, 0.2}, {1.5, 0.5, 0.5}};
  c.labels = {2, 3, 3, 4};
  const Cloud d = voxelDownsample(c, 1.0);
  REQUIRE(d.size() == 2);
  CHECK((d.points[0] - Eigen::Vector3d(0.2, 0.2, 0.2)).norm() < 1e-12);
  CHECK(d.labels[0] == 3);
  CHECK(d.labels[1] == 4);
  CHECK_THROWS_AS(voxelDownsample(c, 0.0), InputError);
  c.labels.pop_back();
  CHECK_THROWS_AS(voxelDownsample(c, 1.0), InputError);
}

TEST_CASE("plane-regularised covariances have their small axis along the surface normal") {
  Cloud c;
  for (int i = -10; i <= 10; ++i)
    for (int j = -10; j <= 10; ++j) c.points.emplace_back(0.2 * i, 0.2 * j, 0.0);
  estimateCovariances(c, 10, 1.0);
  const Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
  for (const auto& C : c.covariances) {
    CHECK(n.dot(C * n) == Approx(1e-3).margin(1e-6));
    CHECK(Eigen::Vector3d::UnitX().dot(C * Eigen::Vector3d::UnitX()) == Approx(1.0).margin(1e-6));
  }
}

TEST_CASE("GICP recovers a known transform on a synthetic structured scene") {
  const Cloud target_raw = structuredScene(1);
  const Pose3 T_true = poseFromXyzRpy(0.6, -0.3, 0.1, 1.0 * kDeg, -0.8 * kDeg, 4.0 * kDeg);
  // Source: an independent sample of the same scene seen from T_true (p_t = T_true p_s).
  const Cloud source_raw = transformCloud(structuredScene(2), T_true.inverse());
  const Cloud source = prepare(source_raw, 0.25);
  const GicpTarget target(prepare(target_raw, 0.25), 1.5);
  GicpSettings s;
  s.max_correspondence_distance = 1.5;
  for (bool labels : {false, true}) {
    s.same_label_only = labels;
    const GicpResult r = alignGicp(target, source, Pose3::Identity(), s);
    INFO("labels " << labels << " iterations " << r.iterations << " rmse " << r.rmse);
    CHECK(r.converged);
    CHECK(transErr(r.T_target_source, T_true) < kSyntheticTransTol);
    CHECK(rotErr(r.T_target_source, T_true) < kSyntheticRotTol);
    CHECK(r.fitness > 0.9);
    // The Hessian is symmetric positive definite (the pose is fully constrained).
    CHECK((r.hessian - r.hessian.transpose()).norm() < 1e-6 * r.hessian.norm());
    CHECK(Eigen::SelfAdjointEigenSolver<Matrix6d>(r.hessian).eigenvalues().minCoeff() > 0);
  }
}

TEST_CASE("point-to-point ICP and threads give consistent answers") {
  const Cloud target_raw = structuredScene(3);
  const Pose3 T_true = poseFromXyzRpy(0.3, 0.2, 0.0, 0.0, 0.0, 2.0 * kDeg);
  const Cloud source = prepare(transformCloud(target_raw, T_true.inverse()), 0.25);
  const GicpTarget target(prepare(target_raw, 0.25), 1.0);
  GicpSettings s;
  const GicpResult one = alignGicp(target, source, Pose3::Identity(), s);
  s.num_threads = 2;
  const GicpResult two = alignGicp(target, source, Pose3::Identity(), s);
  CHECK(transErr(one.T_target_source, two.T_target_source) < 1e-9);
  CHECK(one.iterations == two.iterations);
  s.point_to_point = true;
  s.max_iterations = 100;
  const GicpResult icp = alignGicp(target, source, Pose3::Identity(), s);
  CHECK(transErr(icp.T_target_source, T_true) < 0.1);
  CHECK(rotErr(icp.T_target_source, T_true) < 0.5 * kDeg);
}

TEST_CASE("GICP rejects inconsistent inputs") {
  Cloud src;
  src.points = {{0, 0, 0}};
  const GicpTarget target(structuredScene(4), 1.0);
  GicpSettings s;
  CHECK_THROWS_AS(alignGicp(target, src, Pose3::Identity(), s), InputError);
  s.point_to_point = true;
  s.same_label_only = true;
  CHECK_THROWS_AS(alignGicp(target, src, Pose3::Identity(), s), InputError);
  s.same_label_only = false;
  const GicpResult r = alignGicp(target, src, Pose3::Identity(), s);  // too few inliers
  CHECK_FALSE(r.converged);
}

TEST_CASE("GICP on real KITTI scans: known transform and cycle consistency") {
  const auto dir = test::requireShared("data/kitti_odometry/sequences/00/velodyne");
  const Cloud raw0 = loadKittiScan(dir / "000000.bin");
  REQUIRE(raw0.size() > 100000);
  GicpSettings s;
  s.max_correspondence_distance = 1.0;
  s.num_threads = 2;
  {  // scan 0 against itself moved by a known transform, re-voxelised (different points)
    const Pose3 T_true = poseFromXyzRpy(0.8, 0.1, 0.05, 0.5 * kDeg, 0.3 * kDeg, 2.0 * kDeg);
    const GicpTarget target(prepare(raw0, 0.25), 1.0);
    const Cloud source = prepare(transformCloud(raw0, T_true.inverse()), 0.25);
    const GicpResult r = alignGicp(target, source, Pose3::Identity(), s);
    INFO("iterations " << r.iterations << " rmse " << r.rmse);
    CHECK(r.converged);
    CHECK(transErr(r.T_target_source, T_true) < kRealTransTol);
    CHECK(rotErr(r.T_target_source, T_true) < kRealRotTol);
  }
  // Consecutive scans: T_0_1 * T_1_2 must agree with the direct T_0_2.
  std::vector<Cloud> c;
  for (const char* f : {"000000.bin", "000001.bin", "000002.bin"})
    c.push_back(prepare(loadKittiScan(dir / f), 0.25));
  auto reg = [&](int t, int src, const Pose3& init) {
    const GicpResult r = alignGicp(GicpTarget(c[t], 1.0), c[src], init, s);
    CHECK(r.converged);
    return r.T_target_source;
  };
  const Pose3 T01 = reg(0, 1, Pose3::Identity());
  const Pose3 T12 = reg(1, 2, Pose3::Identity());
  const Pose3 T02 = reg(0, 2, T01 * T01);
  INFO("steps " << T01.translation().norm() << " " << T12.translation().norm());
  CHECK(transErr(T01 * T12, T02) < kCycleTransTol);
  CHECK(rotErr(T01 * T12, T02) < kCycleRotTol);
  CHECK(T01.translation().x() > 0.5);  // the car drives forward (x) about 0.7-0.9 m per frame
  CHECK(T01.translation().x() < 1.0);
}

TEST_CASE("SGICP on a lone straight line: lateral offset recovered, the free direction left alone",
          "[fusion][gicp]") {
  // A painted line along x, its points free along it (sigma 10 m) and tight across (5 cm), as
  // align's element clouds are. Only the lateral offset and height are observable.
  constexpr double kLateralTol = 0.02;  // m
  auto line = [](double phase) {
    Cloud c;
    for (double x = phase; x < 60.0; x += 0.25) {
      c.points.push_back({x, 0.0, 0.0});
      c.covariances.push_back(Eigen::Vector3d(100.0, 0.0025, 0.0025).asDiagonal());
      c.labels.push_back(0);
    }
    return c;
  };
  const Pose3 T_true = poseFromXyzRpy(0.0, 0.6, 0.05, 0.0, 0.0, 0.0);  // source seen 0.6 m aside
  const Cloud source = transformCloud(line(0.1), T_true.inverse());
  const GicpTarget target(line(0.0), 1.5);
  GicpSettings s;
  s.max_correspondence_distance = 1.5;
  s.same_label_only = true;
  s.min_information = 10.0;
  const GicpResult r = alignGicp(target, source, Pose3::Identity(), s);
  INFO("iterations " << r.iterations);
  CHECK(r.converged);
  CHECK(r.iterations < s.max_iterations);
  CHECK(std::abs(r.T_target_source.translation().y() - 0.6) < kLateralTol);
  CHECK(std::abs(r.T_target_source.translation().z() - 0.05) < kLateralTol);
  CHECK(std::abs(r.T_target_source.translation().x()) < kLateralTol);  // left where it started
  // the Hessian says so: its smallest eigenvalue is below the threshold
  CHECK(Eigen::SelfAdjointEigenSolver<Matrix6d>(r.hessian).eigenvalues()(0) < s.min_information);
}
