#pragma once
/// @file KITTI odometry poses files: one pose per line, 12 numbers = the first three rows of a
/// 4x4 matrix, row-major. mapfuse's convention (docs/kitti.md, "Poses files"): `poses.txt` holds
/// T_world_cam0 (rectified left grey camera 0, world = camera 0 of the first pose, the KITTI
/// devkit's, evo's and SemanticKITTI's convention); `poses_velo.txt` holds T_map_velo, the
/// Velodyne poses in the frame of the map written beside it.
#include <filesystem>
#include <string>
#include <vector>

#include "mapfuse/core/se3.hpp"

namespace mapfuse::io {

/// @brief Reads a poses file; every rotation is re-orthonormalised (files carry ~7 digits).
/// @throws IoError when unreadable; ParseError(file, "line <n>") for a line without 12 finite
/// numbers or whose rotation is not one (|R^T R - I| > 1e-3 or det(R) <= 0, e.g. a singular
/// row) or whose translation is beyond bounds::kMaxCoordinate; ParseError(file) when the file
/// holds no pose.
std::vector<Pose3> readKittiOdometryPoses(const std::filesystem::path& path);
/// @brief The same from the text of a file; `file` names it in errors.
std::vector<Pose3> parseKittiOdometryPoses(const std::string& text, const std::string& file);

/// @brief Writes poses atomically in the same format (%.12e: rotations orthonormal to ~1e-12).
void writeKittiOdometryPoses(const std::filesystem::path& path, const std::vector<Pose3>& poses);

}  // namespace mapfuse::io
