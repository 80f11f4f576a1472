#pragma once
/// @file Camera calibration files for lsm-build: the simulator's calibration.json
/// ("mapfuse.camera_calibration", docs/formats-frames.md) and a KITTI raw date folder
/// (P_rect_02 of calib_cam_to_cam.txt plus a given camera height).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "mapfuse/core/drive_records.hpp"

namespace mapfuse::io {

constexpr const char* kCameraCalibFormat = "mapfuse.camera_calibration";

/// @brief Reads calibration.json. Checks K (positive focal lengths, last row 0 0 1), image
/// size (bounds::kMaxImageSide, kMaxImagePixels), a unit ground normal pointing up in the image
/// sense, a positive camera height and T_body_cam within bounds::kMaxExtrinsic.
/// @throws IoError when unreadable; ParseError naming the file and field.
CameraCalib readCameraCalib(const std::filesystem::path& path);
/// @brief The same from a parsed document; `file` names it in errors.
CameraCalib cameraCalibFromJson(const nlohmann::json& doc, const std::string& file);

/// @brief Camera 2 of a KITTI raw date folder: K from P_rect_02, image size from S_rect_02,
/// T_body_cam with body = the OXTS IMU frame (x forward, y left, z up) when
/// calib_imu_to_velo.txt is present (else a level camera), camera height as given, ground
/// normal = body up axis seen from the camera.
/// @throws IoError / ParseError from the calibration files.
CameraCalib readKittiCameraCalib(const std::filesystem::path& date_dir, double camera_height);

}  // namespace mapfuse::io
