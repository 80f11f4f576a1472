#pragma once
/// @file KITTI odometry poses files: one pose per line, 12 numbers = the first three rows of a
/// 4x4 matrix, row-major (left camera of frame i in the frame of camera 0 of the first frame).
#include <filesystem>
#include <string>
#include <vector>

#include "mapfuse/core/se3.hpp"

namespace mapfuse::io {

/// @brief Reads a poses file. @throws IoError when unreadable; ParseError(file, "line <n>")
/// for a line without 12 finite numbers, whose rotation is not orthonormal (tolerance 1e-3) or
/// whose translation is beyond bounds::kMaxCoordinate.
std::vector<Pose3> readKittiOdometryPoses(const std::filesystem::path& path);
/// @brief The same from the text of a file; `file` names it in errors.
std::vector<Pose3> parseKittiOdometryPoses(const std::string& text, const std::string& file);

/// @brief Writes poses atomically in the same format (%.9e).
void writeKittiOdometryPoses(const std::filesystem::path& path, const std::vector<Pose3>& poses);

}  // namespace mapfuse::io
