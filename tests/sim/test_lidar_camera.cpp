// Camera ground truth of the LiDAR simulator: the true label image agrees with the projected
// labelled points; the network-error model corrupts it by the configured amounts.
#include <catch2/catch.hpp>
#include <cmath>

#include "mapfuse/io/kitti_raw_writer.hpp"
#include "mapfuse/sim/lidar_camera.hpp"
#include "mapfuse/sim/lidar_drive.hpp"
#include "mapfuse/sim/lidar_network_error.hpp"
#include "mapfuse/sim/lidar_scene_generator.hpp"
#include "mapfuse/sim/lidar_sensor.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;
using namespace mapfuse::sim;

namespace {
constexpr double kMinAgreement = 0.95;      // share of projected points on a pixel of their class
constexpr double kProbSumTol = 8.0 / 255;   // quantisation of 8 channels
constexpr double kConfusedShareTol = 0.15;  // smooth random regions: share over one image varies

struct Setup {
  io::KittiCalibration calib;
  LidarScene scene;
  Pose3 T_world_velo;
};

Setup makeSetup(uint64_t seed, double s) {
  const auto dir = test::tempDir("lidar_camera_calib");
  io::writeKittiCalibration(dir);
  io::KittiCalibration calib = io::readKittiCalibration(dir);
  StreetParams sp;
  sp.ego_start = s;  // moving cars are placed relative to the ego
  LidarScene scene = generateStreet(sp, seed);
  EgoDrive ego;
  ego.start = s;
  const Pose3 T_imu_velo = calib.T_velo_imu.inverse();
  const Pose3 T = egoImuPose(scene.road(), ego, T_imu_velo, 0.0) * T_imu_velo;
  return {calib, std::move(scene), T};
}
}  // namespace

TEST_CASE("lidar camera: the true label image agrees with the projected labelled points") {
  for (uint64_t seed : {1u, 5u}) {
    const Setup s = makeSetup(seed, 45.0);
    const CameraFrame cam = renderLabels(s.scene, s.calib, s.T_world_velo, 0.0, 80.0);
    REQUIRE(cam.width == 1242);
    REQUIRE(cam.height == 375);
    const LidarScan scan = scanLidar(s.scene, s.T_world_velo, 0.0, LidarSensorParams{}, 11);
    std::size_t seen = 0, agree = 0;
    for (std::size_t i = 0; i < scan.points.size(); ++i) {
      const Eigen::Vector3d p = scan.points[i].head<3>().cast<double>();
      if (p.norm() > 80.0) continue;
      double u, v;
      if (!projectToImage2(s.calib, p, u, v)) continue;
      const long ui = std::lround(u), vi = std::lround(v);
      if (ui < 0 || vi < 0 || ui >= cam.width || vi >= cam.height) continue;
      ++seen;
      const auto cls = static_cast<uint8_t>(lidarClassFromSemanticKitti(scan.labels[i] & 0xFFFF));
      agree += cam.labels[static_cast<std::size_t>(vi) * cam.width + ui] == cls;
    }
    INFO("seed " << seed << ": " << agree << " of " << seen << " projected points agree");
    CHECK(seen > 15000);
    CHECK(static_cast<double>(agree) / seen >= kMinAgreement);
  }
}

TEST_CASE("lidar network errors: no errors reproduce the truth, errors match their shares") {
  const Setup s = makeSetup(2, 60.0);
  const CameraFrame cam = renderLabels(s.scene, s.calib, s.T_world_velo, 0.0, 80.0);
  NetworkErrorParams none;
  none.offset_u = none.offset_v = 0.0;
  none.sidewalk_as_road = none.road_as_sidewalk = none.fence_as_building = 0.0;
  none.building_as_fence = none.blobs_per_frame = none.bleed_sigma = 0.0;
  none.confidence = 1.0;
  CHECK(corruptLabels(cam, none, 1) == cam.labels);
  const io::SemanticImage exact = networkProbabilities(cam, none, 1);
  REQUIRE(exact.channels == kNumLidarClasses);
  for (std::size_t i = 0; i < cam.labels.size(); i += 31)
    CHECK(exact.data[i * kNumLidarClasses + cam.labels[i]] == 255);

  // Only sidewalk -> road confusion: about that share of sidewalk pixels turns into road.
  NetworkErrorParams conf = none;
  conf.sidewalk_as_road = 0.3;
  const auto corrupted = corruptLabels(cam, conf, 4);
  std::size_t sidewalk = 0, flipped = 0, other_changes = 0;
  for (std::size_t i = 0; i < cam.labels.size(); ++i) {
    const bool was_sidewalk = cam.labels[i] == static_cast<uint8_t>(LidarClass::kSidewalk);
    sidewalk += was_sidewalk;
    if (was_sidewalk && corrupted[i] == static_cast<uint8_t>(LidarClass::kRoad)) ++flipped;
    if (!was_sidewalk && corrupted[i] != cam.labels[i]) ++other_changes;
  }
  REQUIRE(sidewalk > 10000);
  CHECK(other_changes == 0);
  CHECK(static_cast<double>(flipped) / sidewalk == Approx(0.3).margin(kConfusedShareTol));

  // Default errors: probabilities sum to one, argmax mostly right but not everywhere.
  const io::SemanticImage noisy = networkProbabilities(cam, NetworkErrorParams{}, 9);
  std::size_t labelled = 0, right = 0;
  for (std::size_t i = 0; i < cam.labels.size(); ++i) {
    const uint8_t* p = noisy.data.data() + i * kNumLidarClasses;
    int sum = 0, best = 0;
    for (int c = 0; c < kNumLidarClasses; ++c) {
      sum += p[c];
      if (p[c] > p[best]) best = c;
    }
    if (i % 101 == 0) CHECK(std::abs(sum / 255.0 - 1.0) <= kProbSumTol);
    if (cam.labels[i] == 0) continue;
    ++labelled;
    right += best == cam.labels[i];
  }
  const double accuracy = static_cast<double>(right) / labelled;
  CHECK(accuracy > 0.75);
  CHECK(accuracy < 0.99);
  // Same seed, same bytes.
  CHECK(networkProbabilities(cam, NetworkErrorParams{}, 9).data == noisy.data);
}
