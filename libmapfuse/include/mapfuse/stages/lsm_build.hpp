#pragma once
/// @file Stage `lsm-build` (Song et al. 2023 §3): a raw drive (docs/formats-frames.md, or a
/// KITTI raw drive with a poses file) -> one local semantic map (LSM) in the drive's odom
/// frame. Reads the drive (loadDrive: ego-motion, semantics from observations, masks or the
/// fallback perception), runs vehicle::buildLsm, writes the LSM, its picture and the summary.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "mapfuse/core/param.hpp"
#include "mapfuse/vehicle/dead_reckoning.hpp"
#include "mapfuse/vehicle/fallback_perception.hpp"
#include "mapfuse/vehicle/lsm_build.hpp"

namespace mapfuse::stages {

struct LsmBuildParams {
  static constexpr const char* kName = "LsmBuildParams";
  // What to read: the drive's layout and where its semantics and ego-motion come from.
  std::string input_kind = "auto";   ///< auto | frames | kitti_raw
  std::string semantics = "auto";    ///< auto | observations | masks | segmenter
  std::string egomotion = "auto";    ///< auto | imu_wheel | poses | oxts
  std::string poses_frame = "cam0";  ///< cam0 (KITTI odometry) | velo (lidar-semantic-map)
  double camera_height = 1.65;       ///< m, KITTI camera height (frames: from calibration)
  int kitti_last_frame = -1;         ///< KITTI: last frame index used (-1 = all)
  vehicle::PerceptionSettings perception;
  vehicle::DeadReckoningSettings dead_reckoning;
  vehicle::LsmBuildSettings build;
  // What to write.
  std::string format = "json";  ///< LSM encoding: json | cbor
  bool render = true;           ///< write <drive>.bev.png (top-down picture)

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("input_kind", input_kind, "", "drive layout (frames: simulate's; auto: detect)",
      oneOf({"auto", "frames", "kitti_raw"}));
    v("semantics", semantics, "", "semantics source (segmenter: the fallback perception)",
      oneOf({"auto", "observations", "masks", "segmenter"}));
    v("egomotion", egomotion, "", "ego-motion source (poses: needs --poses)",
      oneOf({"auto", "imu_wheel", "poses", "oxts"}));
    v("poses_frame", poses_frame, "",
      "frame of the --poses file: cam0 (KITTI odometry T_world_cam0) or velo (KITTI raw only: "
      "T_world_velo, e.g. lidar-semantic-map poses.txt)",
      oneOf({"cam0", "velo"}));
    perception.visit(v);
    v("camera_height", camera_height, "m", "KITTI camera height above the road", gt(0) & le(100));
    v("kitti_last_frame", kitti_last_frame, "", "KITTI: last frame index used (-1 = all)",
      in(-1, 1e9));
    dead_reckoning.visit(v);
    build.visit(v);
    v("format", format, "", "LSM encoding", oneOf({"json", "cbor"}));
    v("render", render, "", "write a top-down PNG of the LSM");
  }
};

/// Command-line inputs that are not tunables.
struct LsmBuildInputs {
  std::filesystem::path drive;  ///< drive folder
  std::filesystem::path out;    ///< output folder
  std::filesystem::path poses;  ///< KITTI odometry poses file (egomotion = poses)
  std::string drive_id;         ///< override (KITTI: default = folder name)
};

/// A drive as read, ready for vehicle::buildLsm, with what was read to get it.
struct LoadedDrive : vehicle::DriveData {
  std::vector<std::filesystem::path> images;     ///< per frame (KITTI), may be empty
  std::vector<cv::Mat> bev_images;               ///< per frame BEV grey (segmenter only)
  std::string input_kind, semantics, egomotion;  ///< what was actually used
  double perception_seconds = 0.0;               ///< fallback perception time (network incl.)
  double network_seconds = 0.0;                  ///< of which the segmentation network
  int cached_frames = 0;                 ///< segmentations read from perception.segmentation_cache
  int aerial_detections = 0;             ///< sign/light/pole boxes of the fallback perception
  vehicle::LaneStyleCounts lane_styles;  ///< lane pieces typed by the fallback perception
};

/// @brief Reads a drive according to the params (auto-detection of layout, semantics and
/// ego-motion source). @throws IoError, ParseError, InputError, ConfigError.
LoadedDrive loadDrive(const LsmBuildInputs& inputs, const LsmBuildParams& params);

/// @brief loadDrive's simulate frames layout (frames.json): calibration, dead reckoning,
/// observations or masks.
void loadFramesDrive(const LsmBuildInputs& inputs, const LsmBuildParams& params,
                     LoadedDrive& drive);

/// @brief The --poses file (egomotion = poses) as body poses: read and checked (rows,
/// rotations, one per frame) before any image or network work. @throws IoError, ParseError,
/// InputError naming the file; ConfigError for poses_frame velo without a Velodyne.
void loadPosesFile(const LsmBuildInputs& inputs, const LsmBuildParams& params, LoadedDrive& drive);

/// @brief loadDrive's KITTI raw layout: image_02 and its calibration, OXTS ego-motion, the
/// fallback perception.
void loadKittiRawDrive(const LsmBuildInputs& inputs, const LsmBuildParams& params,
                       LoadedDrive& drive);

/// @throws ConfigError "LsmBuildParams::<key> = "<value>". Violated constraint: <rule>" for a
/// source the drive does not have.
[[noreturn]] void refuseLsmBuildParam(const char* key, const std::string& value, const char* rule);

/// @brief A poses file given (--poses) while the drive's ego-motion resolved to another source
/// is refused rather than ignored. @throws ConfigError naming the file.
void refuseUnusedPoses(const LsmBuildInputs& inputs, const std::string& egomotion);

/// What one lsm-build run read, built and wrote.
struct LsmBuildRun {
  std::filesystem::path lsm_file;
  std::string drive_id, input_kind, semantics, egomotion;  ///< what was read and used
  double perception_seconds = 0.0, network_seconds = 0.0;  ///< segmenter only
  vehicle::LsmBuildResult build;
  int cached_frames = 0, aerial_detections = 0;  ///< segmenter only (LoadedDrive's)
  vehicle::LaneStyleCounts lane_styles;          ///< segmenter only (LoadedDrive's)
};

/// @brief lsm-build.summary.json without the wall time: the drive, its sources and the counts
/// (vehicle::toJson of the build).
nlohmann::json toJson(const LsmBuildRun& run);

/// @brief Runs the stage: writes <out>/<drive_id>.lsm.<format>, lsm-build.config.json,
/// lsm-build.summary.json and (render) <drive_id>.bev.png.
/// @throws IoError, ParseError, InputError (exit codes 4, 3, 3); ConfigError for bad params.
LsmBuildRun runLsmBuild(const LsmBuildInputs& inputs, const LsmBuildParams& params);

}  // namespace mapfuse::stages
