// lidar-semantic-map stage: parameters, config mirror, end-to-end on a precomputed-semantics
// drive built from real KITTI data, exit codes of the app.
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>

#include "mapfuse/cli/params.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/kitti_poses.hpp"
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

/// A drive folder with `frames` real sfnd scans (frame `replaced` taken from drive 0005 instead)
/// and synthetic label images: rows below the horizon are road, above are building
/// (precomputed semantics, no network).
fs::path makeDrive(const fs::path& root, int frames = 3, int replaced = -1) {
  const fs::path src = test::requireShared(kDate);
  const fs::path date = root / "2011_09_26";
  fs::create_directories(date / "2011_09_26_drive_test_sync/velodyne_points/data");
  for (const char* f : {"calib_cam_to_cam.txt", "calib_velo_to_cam.txt", "calib_imu_to_velo.txt"})
    fs::copy_file(src / f, date / f);
  const fs::path drive = date / "2011_09_26_drive_test_sync";
  for (int i = 0; i < frames; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "%010d", i);
    fs::copy_file(i == replaced
                      ? src / "2011_09_26_drive_0005_sync/velodyne_points/data/0000000000.bin"
                      : src / "2011_09_26_drive_sfnd_sync/velodyne_points/data" /
                            (std::string(name) + ".bin"),
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
  CHECK_NOTHROW(validateParams(p));
  const auto file =
      io::readDocument(fs::path(MAPFUSE_SOURCE_DIR) / "configs/lidar-semantic-map.json");
  CHECK(file == paramsToJson(p));
  p.map.refinement.knn.k = 0;
  CHECK_THROWS_AS(validateParams(p), ConfigError);
  p = {};
  p.map.refinement.through.vehicle_vote_radius = -0.5;
  CHECK_THROWS_WITH(validateParams(p), Catch::Contains("seen_through_vote_radius"));
  p = {};
  p.map.refinement.through.vehicle_vote_share = 0.0;
  CHECK_THROWS_WITH(validateParams(p), Catch::Contains("seen_through_vote_share"));
}

TEST_CASE("lidar-semantic-map builds a map from precomputed label images", "[lidar][stage]") {
  const auto root = test::tempDir("stage");
  const fs::path drive = makeDrive(root);
  stages::LidarSemanticMapParams p;
  p.map.poses.source = "odometry";
  stages::runLidarSemanticMap(drive, root / "out", p);
  const auto summary = test::readSummary(root / "out", "lidar-semantic-map");
  CHECK(summary["semantics"]["source"] == "precomputed");
  // Error minimisation on by default, with the generated forests and their provenance.
  const auto& em = summary["error_minimization"];
  if (MAPFUSE_FORESTS_GENERATED) {
    CHECK(em["skipped"] == false);
    CHECK_FALSE(em["labels"].empty());
    CHECK(em["classifier_dir"].get<std::string>().find("lidar-classifiers") != std::string::npos);
    CHECK(em["provenance"]["format"] == "mapfuse.lidar_forest_provenance");
  } else {
    CHECK(em["skipped"] == true);  // auto without generated forests: off, with the reason
    CHECK(em["reason"].get<std::string>().find("no generated forests") != std::string::npos);
  }
  CHECK(summary["poses"]["converged_scans"].get<int>() == 2);  // 3 frames: 2 steps
  CHECK(summary["poses"]["untrusted_steps"].empty());
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

namespace {
constexpr double kRoundTripTol = 0.05 * (1 + 1e-6);  // m, one voxel (issue 24), float centres
constexpr double kMinSameVoxels = 0.999;             // share of voxels at exactly the same place

/// Largest distance from a point of `b` to the nearest point of `a` (voxel centres: a brute
/// force over the few points within a 3 x 3 x 3 voxel neighbourhood of a hash of `a`), and the
/// share of `b`'s points that have a point of `a` at the same place.
double maxNearestDistance(const LabeledCloud& a, const LabeledCloud& b, double voxel,
                          double* same_share = nullptr) {
  std::map<std::array<int64_t, 3>, std::vector<Eigen::Vector3f>> grid;
  auto key = [&](const Eigen::Vector3f& p) {
    return std::array<int64_t, 3>{int64_t(std::floor(p.x() / voxel)),
                                  int64_t(std::floor(p.y() / voxel)),
                                  int64_t(std::floor(p.z() / voxel))};
  };
  for (const auto& p : a.points) grid[key(p)].push_back(p);
  double worst = 0;
  std::size_t same = 0;
  for (const auto& p : b.points) {
    const auto k = key(p);
    double best = 1e9;
    for (int64_t dx = -1; dx <= 1; ++dx)
      for (int64_t dy = -1; dy <= 1; ++dy)
        for (int64_t dz = -1; dz <= 1; ++dz) {
          const auto it = grid.find({k[0] + dx, k[1] + dy, k[2] + dz});
          if (it == grid.end()) continue;
          for (const auto& q : it->second) best = std::min(best, double((p - q).norm()));
        }
    worst = std::max(worst, best);
    same += best < 1e-6;
  }
  if (same_share) *same_share = double(same) / double(b.points.size());
  return worst;
}
}  // namespace

TEST_CASE("lidar-semantic-map: its own poses.txt fed back reproduces the map within a voxel",
          "[lidar][stage]") {
  const auto root = test::tempDir("stage-roundtrip");
  const fs::path drive = makeDrive(root, 10);
  stages::LidarSemanticMapParams p;
  p.map.poses.source = "odometry";
  p.frames.stride = 3;  // frames 0, 3, 6, 9: poses.txt has one line per selected frame
  stages::runLidarSemanticMap(drive, root / "a", p);
  const auto a = test::readSummary(root / "a", "lidar-semantic-map");
  REQUIRE(a["poses"]["untrusted_steps"].empty());
  // poses.txt is KITTI's T_world_cam0: rotations orthonormal, the first pose the identity.
  const auto cam = io::readKittiOdometryPoses(root / "a/poses.txt");
  REQUIRE(cam.size() == 4);
  CHECK((cam[0].matrix() - Eigen::Matrix4d::Identity()).cwiseAbs().maxCoeff() < 1e-12);
  // Camera 0 looks along +z: driving forward moves the camera along its z axis.
  CHECK(cam[3].translation().z() > 0.9 * cam[3].translation().norm());
  p.map.poses.source = "auto";
  p.map.poses.poses_file = (root / "a/poses.txt").string();
  stages::runLidarSemanticMap(drive, root / "b", p);
  const auto b = test::readSummary(root / "b", "lidar-semantic-map");
  CHECK(b["poses"]["source"] == "poses_file");
  const auto map_a = io::readPly(root / "a/map.ply"), map_b = io::readPly(root / "b/map.ply");
  CHECK(std::abs(double(map_a.size()) - double(map_b.size())) <= 0.001 * double(map_a.size()));
  double same = 0;
  CHECK(maxNearestDistance(map_a, map_b, p.map.voxel_size, &same) <= kRoundTripTol);
  CHECK(same >= kMinSameVoxels);
  CHECK(maxNearestDistance(map_b, map_a, p.map.voxel_size, &same) <= kRoundTripTol);
  CHECK(same >= kMinSameVoxels);
}

TEST_CASE("lidar-semantic-map: a diverging drive stops before any output is replaced",
          "[lidar][stage]") {
  const auto root = test::tempDir("stage-diverge");
  const fs::path good = makeDrive(root / "good", 8);
  stages::LidarSemanticMapParams p;
  p.map.poses.source = "odometry";
  stages::runLidarSemanticMap(good, root / "out", p);
  std::map<fs::path, std::string> before;
  for (const auto& e : fs::recursive_directory_iterator(root / "out"))
    if (e.is_regular_file()) before[e.path()] = test::readText(e.path());
  REQUIRE(before.count(root / "out/map.ply"));
  const fs::path bad = makeDrive(root / "bad", 8, 5);  // frame 5 from another drive
  CHECK_THROWS_WITH(stages::runLidarSemanticMap(bad, root / "out", p),
                    Catch::Contains("frame 5") && Catch::Contains("odom_max_untrusted = 0"));
  std::size_t files = 0;
  for (const auto& e : fs::recursive_directory_iterator(root / "out")) {
    if (!e.is_regular_file()) continue;
    ++files;
    INFO(e.path());
    REQUIRE(before.count(e.path()));
    CHECK(test::readText(e.path()) == before.at(e.path()));
  }
  CHECK(files == before.size());
  // The app: exit 3 and the frame on stderr.
  const auto app = test::appPath("lidar-semantic-map").string();
  CHECK(test::runCommand(app + " " + bad.string() + " -o " + (root / "out").string() +
                         " --pose-source odometry --quiet 2> " + (root / "err.txt").string()) == 3);
  CHECK_THAT(test::readText(root / "err.txt"), Catch::Contains("frame 5"));
  // One untrusted step tolerated: exit 0, the step listed in the summary.
  p.map.poses.odometry.max_untrusted = 1;
  stages::runLidarSemanticMap(bad, root / "tolerant", p);
  const auto s = test::readSummary(root / "tolerant", "lidar-semantic-map");
  REQUIRE(s["poses"]["untrusted_steps"].size() == 1);
  CHECK(s["poses"]["untrusted_steps"][0]["frame"] == 5);
}
