#pragma once
/// @file Binary PCD v0.7 of a labelled cloud, PCL-compatible (pcl::PointXYZRGBL reads it):
/// FIELDS x y z rgb label confidence semantic_kitti; x, y, z, confidence float32; rgb packed
/// 0x00RRGGBB in the bits of a float32 (TYPE F, PCL's PointXYZRGB convention, which
/// pcl_pcd2ply and Open3D turn into colours); label uint32 (mapfuse LidarClass id 0-7);
/// semantic_kitti uint32 (the SemanticKITTI semantic id of that class, docs/formats.md
/// "LiDAR classes"); header comments say so.
#include <filesystem>
#include <string>

#include "mapfuse/core/labeled_cloud.hpp"

namespace mapfuse::io {

/// @brief Writes the cloud atomically. @throws InputError for inconsistent array sizes.
void writePcd(const std::filesystem::path& path, const LabeledCloud& cloud);

/// @brief Reads a `DATA binary` PCD with fields x, y, z and optional label / confidence
/// (SIZE 4, any order; other fields skipped).
/// @throws IoError when unreadable; ParseError(file, field) for a malformed header, `ascii` or
/// `binary_compressed` data, missing x/y/z, a truncated body, a coordinate beyond
/// bounds::kMaxCoordinate, a label that is no LiDAR class id or a confidence outside [0, 1].
LabeledCloud readPcd(const std::filesystem::path& path);
/// @brief The same from the bytes of a file; `file` names it in errors.
LabeledCloud parsePcd(const std::string& bytes, const std::string& file);

}  // namespace mapfuse::io
