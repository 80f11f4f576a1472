#pragma once
/// @file KITTI Velodyne scans: binary float32 records (x, y, z, reflectance), 16 bytes a point,
/// little-endian, in the Velodyne frame (m).
#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

namespace mapfuse::io {

/// One Velodyne sweep.
struct VelodyneScan {
  std::vector<Eigen::Vector3f> points;  ///< velo frame (m)
  std::vector<float> reflectance;       ///< 0..1, same size as points
  std::size_t size() const { return points.size(); }
};

/// @brief Reads a `.bin` scan.
/// @throws IoError when unreadable; ParseError(file, "size") when the byte count is not a
/// multiple of 16, ParseError(file, "point <i>") for a coordinate that is not finite or beyond
/// bounds::kMaxLidarRange, or a non-finite reflectance.
VelodyneScan readVelodyneBin(const std::filesystem::path& path);
/// @brief The same from the bytes of a file; `file` names it in errors.
VelodyneScan parseVelodyneBin(const std::string& bytes, const std::string& file);

/// @brief Writes a `.bin` scan atomically. @throws InputError if the two arrays differ in size.
void writeVelodyneBin(const std::filesystem::path& path, const VelodyneScan& scan);

}  // namespace mapfuse::io
