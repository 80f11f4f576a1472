// lidar-semantic-map stage: parameters, config mirror, end-to-end on a precomputed-semantics
// drive built from real KITTI data, exit codes of the app.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/kitti_raw.hpp"
#include "mapfuse/io/pcd.hpp"
#include "mapfuse/io/ply.hpp"
#include "mapfuse/io/semantic_image.hpp"
#include "mapfuse/io/semantic_kitti.hpp"
#include "mapfuse/io/velodyne.hpp"
#include "mapfuse/stages/lidar_semantic_map.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;
namespace fs = std::filesystem;

namespace {
const char* const kDate = "data/kitti_raw/2011_09_26";

/// A drive folder with 3 real sfnd scans and synthetic label images: rows below the horizon
/// are road, above are building (precomputed semantics, no network).
fs::path makeDrive(const fs::path& root) {
  const fs::path src = test::requireShared(kDate);
  const fs::path date = root / "2011_09_26";
  fs::create_directories(date / "2011_09_26_drive_test_sync/velodyne_points/data");
  for (const char* f : {"calib_cam_to_cam.txt", "calib_velo_to_cam.txt", "calib_imu_to_velo.txt"})
    fs::copy_file(src / f, date / f);
  const fs::path drive = date / "2011_09_26_drive_test_sync";
  for (int i = 0; i < 3; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "%010d", i);
    fs::copy_file(
        src / "2011_09_26_drive_sfnd_sync/velodyne_points/data" / (std::string(name) + ".bin"),
        drive / "velodyne_points/data" / (std::string(name) + ".bin"));
    std::vector<uint8_t> labels(1242 * 375);
    for (int v = 0; v < 375; ++v)
      for (int u = 0; u < 1242; ++u) labels[v * 1242 + u] = v > 190 ? 1 : 3;
    io::writeSemanticImage(drive / "semantics_02" / (std::string(name) + ".png"),
                           io::SemanticImage::fromLabels(1242, 375, labels));
  }
  return drive;
}
}  // namespace

TEST_CASE("lidar-semantic-map defaults are valid and configs/ mirrors them", "[lidar][stage]") {
  stages::LidarSemanticMapParams p;
  CHECK_NOTHROW(p.validate());
  const auto file =
      io::readDocument(fs::path(MAPFUSE_SOURCE_DIR) / "configs/lidar-semantic-map.json");
  CHECK(file == paramsToJson(p));
  p.knn_k = 0;
  CHECK_THROWS_AS(p.validate(), ConfigError);
  p = {};
  p.seen_through_vote_radius = -0.5;
  CHECK_THROWS_WITH(p.validate(), Catch::Contains("seen_through_vote_radius"));
  p = {};
  p.seen_through_vote_share = 0.0;
  CHECK_THROWS_WITH(p.validate(), Catch::Contains("seen_through_vote_share"));
}

TEST_CASE("lidar-semantic-map builds a map from precomputed label images", "[lidar][stage]") {
  const auto root = test::tempDir("stage");
  const fs::path drive = makeDrive(root);
  stages::LidarSemanticMapParams p;
  p.pose_source = "odometry";
  const auto summary = stages::runLidarSemanticMap(drive, root / "out", p);
  CHECK(summary["semantics"]["source"] == "precomputed");
  CHECK(summary["error_minimization"]["skipped"] == true);
  CHECK(summary["poses"]["converged_scans"].get<int>() >= 2);
  const auto ply = io::readPly(root / "out/map.ply");
  const auto pcd = io::readPcd(root / "out/map.pcd");
  CHECK(ply.size() == summary["voxels"].get<std::size_t>());
  CHECK(pcd.size() == ply.size());
  // only road (1) and building (3) can appear
  std::size_t other = 0;
  for (uint8_t l : ply.labels) other += (l != 1 && l != 3);
  CHECK(other == 0);
  for (int i = 0; i < 3; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "%010d", i);
    const auto labels =
        io::readSemanticKittiLabels(root / "out/labels" / (std::string(name) + ".label"));
    const auto scan =
        io::readVelodyneBin(drive / "velodyne_points/data" / (std::string(name) + ".bin"));
    CHECK(labels.size() == scan.size());
  }
  CHECK(fs::exists(root / "out/topdown.png"));
  CHECK(summary["bytes_per_voxel"].get<double>() <= 64.0);
}

TEST_CASE("lidar-semantic-map app: exit codes", "[lidar][stage]") {
  const auto root = test::tempDir("stage-app");
  const auto app = test::appPath("lidar-semantic-map").string();
  CHECK(test::runCommand(app + " --help > /dev/null") == 0);
  CHECK(test::runCommand(app + " " + (root / "missing").string() + " -o " + (root / "o").string() +
                         " 2>/dev/null") == 4);
  CHECK(test::runCommand(app + " x -o y --knn-k 0 2>/dev/null") == 2);
  const fs::path drive = makeDrive(root);
  // truncated scan -> bad input
  {
    std::string bytes = test::readText(drive / "velodyne_points/data/0000000001.bin");
    test::writeText(drive / "velodyne_points/data/0000000001.bin",
                    bytes.substr(0, bytes.size() - 3));
  }
  CHECK(test::runCommand(app + " " + drive.string() + " -o " + (root / "o").string() +
                         " --pose-source odometry --quiet 2>/dev/null") == 3);
  CHECK_FALSE(fs::exists(root / "o/map.ply"));
}
