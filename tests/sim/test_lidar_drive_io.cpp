// The synthetic KITTI raw drive through the project's KITTI reader: Velodyne, labels, OXTS
// poses, timestamps, calibration and probabilities come back bit-exactly; same seed, same bytes;
// params mirror configs/simulate-lidar.json; app exit codes.
#include <catch2/catch.hpp>
#include <cstring>
#include <fstream>

#include "mapfuse/cli/params.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/kitti_raw.hpp"
#include "mapfuse/io/kitti_raw_writer.hpp"
#include "mapfuse/io/oxts_line.hpp"
#include "mapfuse/io/semantic_image.hpp"
#include "mapfuse/io/semantic_kitti.hpp"
#include "mapfuse/io/velodyne.hpp"
#include "mapfuse/lidar/drive_poses.hpp"
#include "mapfuse/sim/lidar_camera.hpp"
#include "mapfuse/sim/lidar_drive.hpp"
#include "mapfuse/stages/simulate_lidar.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;

namespace {
constexpr double kPoseTol = 1e-6;  // m / rad: devkit Mercator pose vs true pose
constexpr double kTimeTol = 1e-9;  // s: timestamps are written to the nanosecond

stages::SimulateLidarParams smallParams() {
  stages::SimulateLidarParams p;
  p.seed = 17;
  p.lidar.frames = 3;
  p.lidar.sensor.azimuth_steps = 256;
  p.drive = "0042";
  return p;
}

std::string fileBytes(const std::filesystem::path& p) {
  return test::readText(p);
}
}  // namespace

TEST_CASE("lidar drive io: write -> KITTI reader round trip is bit-exact") {
  const auto out = test::tempDir("lidarsim_roundtrip");
  const auto P = smallParams();
  const auto summary = stages::toJson(stages::runSimulateLidar(out, P));
  const auto drive_dir = io::kittiDriveDir(out, P.date, P.drive);
  REQUIRE(summary["drive_dir"].get<std::string>() == drive_dir.string());

  const io::KittiRawDrive drive = io::openKittiRawDrive(drive_dir, io::FrameRange{});
  REQUIRE(drive.frames.size() == 3);
  REQUIRE(drive.has_oxts);
  REQUIRE(drive.calib.has_imu);

  // Rebuild the truth in memory exactly as the stage does.
  const sim::StreetParams& street = P.lidar.street;
  const sim::LidarScene scene = sim::generateStreet(street, static_cast<uint64_t>(P.seed));
  const Pose3 T_imu_velo = drive.calib.T_velo_imu.inverse();
  const sim::EgoDrive ego{street.ego_start, street.ego_speed, -0.5 * street.profile.lane_width,
                          P.lidar.velo_height};
  const std::vector<Pose3> read_poses = lidar::oxtsVeloPoses(drive, /*enu=*/false);
  const Pose3 T0 = sim::egoImuPose(scene.road(), ego, T_imu_velo, 0.0) * T_imu_velo;
  for (std::size_t k = 0; k < drive.frames.size(); ++k) {
    const auto& f = drive.frames[k];
    const double t = k / P.lidar.frame_rate;
    const Pose3 T_world_velo = sim::egoImuPose(scene.road(), ego, T_imu_velo, t) * T_imu_velo;
    const sim::LidarScan scan =
        sim::scanLidar(scene, T_world_velo, t, P.lidar.sensor, sim::hashKey(P.seed, k, 1));
    const io::VelodyneScan read = io::readVelodyneBin(f.velodyne);
    REQUIRE(read.size() == scan.points.size());
    for (std::size_t i = 0; i < read.size(); ++i) {
      REQUIRE(std::memcmp(read.points[i].data(), scan.points[i].data(), 12) == 0);
      REQUIRE(read.reflectance[i] == scan.points[i].w());
    }
    CHECK(io::readSemanticKittiLabels(drive_dir / "labels" / (f.name + ".label")) == scan.labels);
    // OXTS -> devkit pose reproduces the true motion relative to frame 0.
    const Pose3 truth_rel = T0.inverse() * T_world_velo;
    const Pose3 read_rel = read_poses[0].inverse() * read_poses[k];
    CHECK((truth_rel.translation() - read_rel.translation()).norm() < kPoseTol);
    CHECK((truth_rel.linear() - read_rel.linear()).norm() < kPoseTol);
    CHECK((read_poses[k].translation() - read_poses[0].translation() -
           (T_world_velo.translation() - T0.translation()))
              .norm() < kPoseTol);
    CHECK(f.timestamp == Approx(P.start_time + t).margin(kTimeTol));
    CHECK(f.scan_start < f.timestamp);
    CHECK(f.scan_end > f.timestamp);
    // Probabilities read back equal the model's output.
    const sim::CameraFrame cam =
        sim::renderLabels(scene, drive.calib, T_world_velo, t, P.lidar.camera_max_range);
    const io::SemanticImage probs =
        sim::networkProbabilities(cam, P.lidar.network, sim::hashKey(P.seed, k, 2));
    const auto sem = io::findSemanticImage(drive_dir, f.name);
    REQUIRE(sem);
    CHECK(io::readSemanticImage(*sem).data == probs.data);
    CHECK(!f.image.empty());
  }
  // OXTS text: frame 0 sits exactly on the configured anchor.
  const geo::OxtsRecord r0 = io::readOxts(drive.frames[0]);
  CHECK(r0.lat == P.lat0);
  CHECK(r0.lon == P.lon0);
  // Calibration: the same matrices as the real KITTI 2011_09_26 calibration.
  CHECK(drive.calib.image_width == 1242);
  CHECK(drive.calib.image_height == 375);
}

TEST_CASE("lidar drive io: calibration files equal the real KITTI 2011_09_26 files") {
  const auto real = test::requireShared("data/kitti_raw/2011_09_26");
  const auto dir = test::tempDir("lidarsim_calib");
  io::writeKittiCalibration(dir);
  for (const char* name :
       {"calib_cam_to_cam.txt", "calib_velo_to_cam.txt", "calib_imu_to_velo.txt"})
    CHECK(fileBytes(dir / name) == fileBytes(real / name));
  io::writeOxtsDataformat(dir / "dataformat.txt");
  CHECK(fileBytes(dir / "dataformat.txt") ==
        fileBytes(real / "2011_09_26_drive_0005_sync/oxts/dataformat.txt"));
}

TEST_CASE("lidar drive io: OXTS lines and timestamps parse back exactly") {
  io::MercatorAnchor a;
  const Pose3 T = poseFromXyzRpy(123.25, -48.5, 2.0, 0.01, -0.02, 2.5);
  const geo::OxtsRecord r = io::oxtsFromPose(T, a);
  const geo::OxtsRecord back = io::parseOxtsLine(io::formatOxtsLine(r), "x.txt");
  CHECK(back.lat == r.lat);
  CHECK(back.lon == r.lon);
  CHECK(back.yaw == r.yaw);
  CHECK(back.navstat == r.navstat);
  const double s = geo::mercatorScale(a.lat0);
  const Pose3 P0 = geo::oxtsToMercatorPose(io::oxtsFromPose(Pose3::Identity(), a), s);
  const Pose3 P1 = geo::oxtsToMercatorPose(back, s);
  CHECK((P1.translation() - P0.translation() - T.translation()).norm() < kPoseTol);
  CHECK((P1.linear() - T.linear()).norm() < kPoseTol);
  CHECK(io::formatKittiTimestamp("2011_09_26", 13 * 3600 + 4 * 60 + 32.345808896) ==
        "2011-09-26 13:04:32.345808896");
  CHECK(io::parseKittiTimestamp(io::formatKittiTimestamp("2011_09_26", 43200.1), "t", "0") ==
        Approx(43200.1).margin(kTimeTol));
}

TEST_CASE("lidar drive io: same seed gives the same bytes") {
  auto P = smallParams();
  P.lidar.frames = 2;
  const auto a = test::tempDir("lidarsim_det_a"), b = test::tempDir("lidarsim_det_b");
  stages::runSimulateLidar(a, P);
  stages::runSimulateLidar(b, P);
  std::size_t files = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(a)) {
    if (!e.is_regular_file() || e.path().filename() == "simulate-lidar.summary.json") continue;
    const auto rel = std::filesystem::relative(e.path(), a);
    INFO(rel.string());
    CHECK(fileBytes(e.path()) == fileBytes(b / rel));
    ++files;
  }
  CHECK(files > 20);
}

TEST_CASE("lidar drive io: configs/simulate-lidar.json mirrors the defaults, which are valid") {
  const auto j = io::readDocument(std::filesystem::path(MAPFUSE_SOURCE_DIR) / "configs" /
                                  "simulate-lidar.json");
  CHECK(j == paramsToJson(stages::SimulateLidarParams{}));
  CHECK_NOTHROW(validateParams(stages::SimulateLidarParams{}));
  stages::SimulateLidarParams bad;
  bad.lidar.street.turn_radius_min = 4.0;
  try {
    validateParams(bad);
    FAIL("expected ConfigError");
  } catch (const ConfigError& e) {
    CHECK(std::string(e.what()).find("turn_radius_min") != std::string::npos);
  }
}

TEST_CASE("lidar drive io: simulate-lidar app exit codes") {
  const auto dir = test::tempDir("lidarsim_app");
  const std::string app = test::appPath("simulate-lidar").string();
  CHECK(test::runCommand(app + " --help > /dev/null") == 0);
  CHECK(test::runCommand(app + " 2>/dev/null") == 2);  // --out is required
  CHECK(test::runCommand(app + " -o " + (dir / "o").string() + " --frames 0 2>/dev/null") == 2);
  test::writeText(dir / "bad.json", R"({"frames": 2, "no_such_key": 1})");
  CHECK(test::runCommand(app + " -o " + (dir / "o").string() + " --config " +
                         (dir / "bad.json").string() + " 2>/dev/null") == 2);
  // A drive longer than the generated road is a usage error naming the parameter.
  CHECK(test::runCommand(app + " -o " + (dir / "o").string() + " --frames 100000 2>/dev/null") ==
        2);
  test::writeText(dir / "blocker", "a file where the output folder should be");
  CHECK(test::runCommand(app + " -o " + (dir / "blocker").string() +
                         " --frames 1 --azimuth-steps 64 2>/dev/null") == 4);
}
