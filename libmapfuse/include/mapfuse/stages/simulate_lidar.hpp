#pragma once
/// @file Stage `simulate-lidar`: a seeded synthetic KITTI raw drive with LiDAR + camera ground
/// truth (docs/lidar-ground-truth.md). Writes `<out>/<date>/calib_*.txt` and
/// `<out>/<date>/<date>_drive_<drive>_sync/` with image_02, velodyne_points, oxts, timestamps,
/// `semantics_02/<frame>.prob` (network-like probabilities), `labels/<frame>.label` (true
/// SemanticKITTI labels, moving cars 252, instance ids in the upper 16 bits) and
/// `ground_truth/` (true label images, true poses), plus simulate-lidar.{config,summary}.json.
/// The simulation itself is sim::LidarDrive; this stage writes its frames in the KITTI layout.
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "mapfuse/core/param.hpp"
#include "mapfuse/sim/lidar_drive.hpp"

namespace mapfuse::stages {

/// @brief True for a KITTI date folder name, YYYY_MM_DD.
bool isKittiDate(const std::string& text);

struct SimulateLidarParams {
  static constexpr const char* kName = "SimulateLidarParams";
  int64_t seed = 1;                 ///< scene and noise seed
  std::string date = "2011_09_26";  ///< KITTI date folder name (YYYY_MM_DD)
  std::string drive = "0001";       ///< drive name: <date>_drive_<drive>_sync
  sim::LidarDriveSettings lidar;    ///< frames, street, LiDAR, camera and network errors
  // Geography of the written OXTS and timestamps.
  double lat0 = 49.011212804408;  ///< deg, latitude of frame 0
  double lon0 = 8.4228850417969;  ///< deg
  double alt0 = 112.83;           ///< m
  double start_time = 43200.0;    ///< s after midnight of `date` of frame 0

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("seed", seed, "", "seed of the scene and of every noise draw", in(0, 4294967295.0));
    v("date", date, "", "KITTI date folder name", TextRule{isKittiDate, "YYYY_MM_DD"});
    v("drive", drive, "", "drive name: <date>_drive_<drive>_sync",
      TextRule{[](const std::string& d) { return !d.empty() && d.find('/') == std::string::npos; },
               "non-empty, no '/'"});
    lidar.visit(v);
    v("lat0", lat0, "deg", "latitude of frame 0", gt(-85) & lt(85));
    v("lon0", lon0, "deg", "longitude of frame 0", in(-180, 180));
    v("alt0", alt0, "m", "altitude of the road at frame 0's IMU position, plus IMU height",
      in(-10000, 100000));
    v("start_time", start_time, "s", "time of frame 0 after midnight of the date", in(0, 86400));
    v.relation("start_time", start_time, start_time + lidar.frames / lidar.frame_rate < 86400.0,
               "+ frames / frame_rate < 86400 (the drive ends before midnight)");
  }
};

/// What one simulate-lidar run wrote (simulate-lidar.summary.json).
struct SimulateLidarRun {
  std::filesystem::path drive_dir;
  int frames = 0;
  double road_length = 0.0;  ///< m
  std::size_t primitives = 0, moving_vehicles = 0;
  sim::LidarScanStats points;
  double seconds_lidar = 0, seconds_camera = 0, seconds_write = 0, seconds_total = 0;
};

/// @brief The summary document.
nlohmann::json toJson(const SimulateLidarRun& run);

/// @brief Generates the drive under `out` (see file comment).
/// @throws ConfigError for invalid params; IoError when writing fails.
SimulateLidarRun runSimulateLidar(const std::filesystem::path& out,
                                  const SimulateLidarParams& params);

}  // namespace mapfuse::stages
