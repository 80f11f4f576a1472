#pragma once
/// @file KITTI odometry / SemanticKITTI sequence folders, `sequences/NN/` with velodyne/*.bin,
/// image_2/*.png, calib.txt (P0-P3 and Tr: Velodyne -> rectified camera 0), times.txt (s,
/// optional), poses.txt (T_world_cam0, SemanticKITTI; optional) and labels/*.label (optional),
/// opened into the same KittiRawDrive as a raw drive (docs/kitti.md). Frame names are the
/// six-digit file stems.
#include <filesystem>

#include "mapfuse/io/kitti_raw.hpp"

namespace mapfuse::io {

/// @brief True when `dir` holds velodyne/ (and no velodyne_points/).
/// @throws IoError naming calib.txt when such a folder has none.
bool isKittiSequence(const std::filesystem::path& dir);

/// @brief Calibration of a sequence: P_rect_02 = P2, R_rect_00 = I, T_cam0_velo = Tr (already
/// rectified), no IMU; image size from the first image_2 PNG (0 x 0 without images).
/// @throws IoError when calib.txt is unreadable; ParseError naming the key when malformed.
KittiCalibration readKittiSequenceCalibration(const std::filesystem::path& sequence_dir);

/// @brief Lists a sequence's frames (as openKittiRawDrive does for a raw drive).
/// @throws IoError when velodyne/ is missing; InputError when no frame is selected;
/// ParseError for calib.txt or times.txt.
KittiRawDrive openKittiSequence(const std::filesystem::path& sequence_dir, const FrameRange& range);

}  // namespace mapfuse::io
