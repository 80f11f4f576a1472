#pragma once
/// @file The raw drive folder that lsm-build reads (docs/formats-frames.md): manifest,
/// calibration, IMU / wheel / GPS streams, frame list, masks, observations and (optional)
/// truth poses; plus KITTI odometry poses files (12 numbers per line, T_world_cam0 row-major).
#include <filesystem>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "mapfuse/core/drive_records.hpp"
#include "mapfuse/core/lsm.hpp"

namespace mapfuse::io {

constexpr const char* kFramesFormat = "mapfuse.frames";

/// One camera frame of frames.csv.
struct FrameEntry {
  int index = 0;
  double stamp = 0.0;          ///< s
  std::filesystem::path mask;  ///< absolute path of the mask PNG (may be empty)
};

/// A drive folder, loaded except for the mask images (read one by one with readMask).
struct DriveFrames {
  std::filesystem::path dir;
  std::string drive_id;
  std::string vehicle_id;
  std::optional<geo::GeoOrigin> origin;  ///< of the truth poses only
  CameraCalib calib;
  std::vector<ImuSample> imu;
  std::vector<WheelSample> wheel;
  std::vector<GpsFix> gps;
  std::vector<FrameEntry> frames;
  std::vector<FrameObservations> observations;  ///< empty when the file is absent
  std::vector<Pose3> truth_T_enu_body;          ///< per frame, empty when absent
};

/// @brief Reads a drive folder (frames.json and everything it names).
/// @throws IoError for missing files; ParseError (file, field/line, problem) for malformed
/// ones; InputError when counts disagree (frame_count vs frames.csv vs observations.jsonl).
DriveFrames readDriveFrames(const std::filesystem::path& dir);

/// @brief Reads one mask PNG (8-bit, one class id per pixel) and checks its size.
/// @throws IoError when missing, ParseError when not a decodable 8-bit single-channel PNG of
/// the expected size.
cv::Mat readMask(const std::filesystem::path& path, int width, int height);

/// @brief KITTI odometry poses: one line per frame, 12 numbers = row-major [R|t] of
/// T_world_cam0. @throws IoError, ParseError(file, "line N") when malformed or a translation is
/// beyond bounds::kMaxCoordinate.
std::vector<Pose3> readKittiPoses(const std::filesystem::path& path);
/// @brief The same from the text of a file; `file` names it in errors.
std::vector<Pose3> parseKittiPoses(const std::string& text, const std::string& file);

}  // namespace mapfuse::io
