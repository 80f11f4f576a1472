#include "mapfuse/io/velodyne.hpp"

#include <cmath>
#include <cstring>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/bounds.hpp"

namespace mapfuse::io {

VelodyneScan parseVelodyneBin(const std::string& bytes, const std::string& file) {
  if (bytes.size() % 16 != 0)
    throw ParseError(file, "size",
                     std::to_string(bytes.size()) +
                         " bytes is not a multiple of 16 (float32 x, y, z, reflectance)");
  const std::size_t n = bytes.size() / 16;
  VelodyneScan scan;
  scan.points.resize(n);
  scan.reflectance.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    float v[4];
    std::memcpy(v, bytes.data() + i * 16, 16);
    for (int k = 0; k < 3; ++k)
      if (!(std::abs(v[k]) <= bounds::kMaxLidarRange))  // also NaN
        throw ParseError(file, "point " + std::to_string(i),
                         "coordinate " + bounds::numberText(v[k]) + " m is not within " +
                             bounds::rangeText(-bounds::kMaxLidarRange, bounds::kMaxLidarRange));
    if (!std::isfinite(v[3]))
      throw ParseError(file, "point " + std::to_string(i), "reflectance is not finite");
    scan.points[i] = Eigen::Vector3f(v[0], v[1], v[2]);
    scan.reflectance[i] = v[3];
  }
  return scan;
}

VelodyneScan readVelodyneBin(const std::filesystem::path& path) {
  return parseVelodyneBin(readBytes(path), path.string());
}

void writeVelodyneBin(const std::filesystem::path& path, const VelodyneScan& scan) {
  if (scan.points.size() != scan.reflectance.size())
    throw InputError(path.string() + ": points and reflectance differ in size");
  std::string bytes(scan.size() * 16, '\0');
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const float v[4] = {scan.points[i].x(), scan.points[i].y(), scan.points[i].z(),
                        scan.reflectance[i]};
    std::memcpy(bytes.data() + i * 16, v, 16);
  }
  writeBytesAtomic(path, bytes);
}

}  // namespace mapfuse::io
