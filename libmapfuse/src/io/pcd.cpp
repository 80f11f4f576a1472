#include "mapfuse/io/pcd.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <sstream>
#include <vector>

#include "cloud_records.hpp"
#include "mapfuse/core/classes.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/bounds.hpp"

namespace mapfuse::io {
namespace {
/// Largest COUNT of one field (values per point).
constexpr int64_t kMaxCount = 1 << 20;
}  // namespace

void writePcd(const std::filesystem::path& path, const LabeledCloud& cloud) {
  std::ostringstream h;
  h << "# .PCD v0.7 - Point Cloud Data file format\n"
    << "# label: mapfuse LiDAR class id 0-7 (docs/formats.md \"LiDAR classes\")\n"
    << "# semantic_kitti: SemanticKITTI semantic id of the class\nVERSION 0.7\n"
    << "FIELDS x y z rgb label confidence semantic_kitti\nSIZE 4 4 4 4 4 4 4\n"
    << "TYPE F F F F U F U\nCOUNT 1 1 1 1 1 1 1\nWIDTH " << cloud.size() << "\nHEIGHT 1\n"
    << "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << cloud.size() << "\nDATA binary\n";
  writeCloudRecords(path, cloud, h.str(), 28, [&](std::size_t i, char* p) {
    std::memcpy(p, cloud.points[i].data(), 12);
    const auto col = lidarClassColor(static_cast<LidarClass>(cloud.labels[i]));
    // PCL's PointXYZRGB convention: 0x00RRGGBB stored in the bits of a float field
    const uint32_t rgb = (uint32_t{col[0]} << 16) | (uint32_t{col[1]} << 8) | col[2];
    const uint32_t label = cloud.labels[i];
    std::memcpy(p + 12, &rgb, 4);
    std::memcpy(p + 16, &label, 4);
    std::memcpy(p + 20, &cloud.confidence[i], 4);
    const uint32_t kitti = semanticKittiId(static_cast<LidarClass>(cloud.labels[i]));
    std::memcpy(p + 24, &kitti, 4);
  });
}

LabeledCloud readPcd(const std::filesystem::path& path) {
  return parsePcd(readBytes(path), path.string());
}

LabeledCloud parsePcd(const std::string& bytes, const std::string& file) {
  std::vector<std::string> fields, types;
  std::vector<int64_t> sizes, counts;
  long long points = -1;
  std::size_t pos = 0;
  bool data = false;
  // A whole number within [lo, hi] of a header line.
  auto integer = [&](const std::string& key, const std::string& tok, int64_t lo, int64_t hi) {
    char* end = nullptr;
    errno = 0;
    const long long v = std::strtoll(tok.c_str(), &end, 10);
    if (errno != 0 || end == tok.c_str() || *end != '\0' || v < lo || v > hi)
      throw ParseError(file, key,
                       "'" + tok + "' is not an integer within [" + std::to_string(lo) + ", " +
                           std::to_string(hi) + "]");
    return int64_t(v);
  };
  while (pos < bytes.size() && !data) {
    const auto eol = bytes.find('\n', pos);
    if (eol == std::string::npos) throw ParseError(file, "header", "ends before DATA");
    std::istringstream ls(bytes.substr(pos, eol - pos));
    pos = eol + 1;
    std::string kw, tok;
    ls >> kw;
    if (kw.empty() || kw[0] == '#') continue;
    if (kw == "FIELDS") {
      while (ls >> tok) fields.push_back(tok);
    } else if (kw == "SIZE") {
      while (ls >> tok) sizes.push_back(integer("SIZE", tok, 1, 8));
    } else if (kw == "TYPE") {
      while (ls >> tok) types.push_back(tok);
    } else if (kw == "COUNT") {
      while (ls >> tok) counts.push_back(integer("COUNT", tok, 1, kMaxCount));
    } else if (kw == "POINTS") {
      if (!(ls >> tok)) throw ParseError(file, "POINTS", "bad count");
      points = integer("POINTS", tok, 0, std::numeric_limits<int64_t>::max());
    } else if (kw == "DATA") {
      ls >> tok;
      if (tok != "binary")
        throw ParseError(file, "DATA", "'" + tok + "' unsupported (binary only)");
      data = true;
    }
  }
  if (!data) throw ParseError(file, "DATA", "missing");
  if (points < 0) throw ParseError(file, "POINTS", "missing");
  if (sizes.size() != fields.size() || types.size() != fields.size())
    throw ParseError(file, "SIZE", "FIELDS, SIZE and TYPE differ in length");
  if (counts.empty()) counts.assign(fields.size(), 1);
  if (counts.size() != fields.size()) throw ParseError(file, "COUNT", "length differs from FIELDS");
  int64_t stride = 0;  // <= fields * 8 * kMaxCount: fields are fewer than the file's bytes
  int64_t ox = -1, oy = -1, oz = -1, ol = -1, oc = -1;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const std::string& f = fields[i];
    if (types[i] != "F" && types[i] != "U" && types[i] != "I")
      throw ParseError(file, "TYPE", "'" + types[i] + "' is not F, U or I");
    if ((f == "x" || f == "y" || f == "z" || f == "confidence") &&
        (sizes[i] != 4 || types[i] != "F"))
      throw ParseError(file, f, "must be SIZE 4 TYPE F");
    if (f == "x") ox = stride;
    if (f == "y") oy = stride;
    if (f == "z") oz = stride;
    if (f == "confidence") oc = stride;
    if (f == "label") {
      if (sizes[i] != 4 || types[i] == "F")
        throw ParseError(file, "label", "must be SIZE 4 TYPE U");
      ol = stride;
    }
    stride += sizes[i] * counts[i];
  }
  if (ox < 0 || oy < 0 || oz < 0) throw ParseError(file, "FIELDS", "x, y, z missing");
  const auto need = bounds::checkedMultiply(points, stride);
  if (!need || uint64_t(*need) > bytes.size() - pos)
    throw ParseError(file, "DATA", "body truncated");
  LabeledCloud c;
  c.points.resize(static_cast<std::size_t>(points));
  c.labels.assign(c.points.size(), 0);
  c.confidence.assign(c.points.size(), 1.0f);
  for (std::size_t i = 0; i < c.points.size(); ++i) {
    const char* p = bytes.data() + pos + i * static_cast<std::size_t>(stride);
    const std::string where = "point " + std::to_string(i);
    float xyz[3];
    std::memcpy(&xyz[0], p + ox, 4);
    std::memcpy(&xyz[1], p + oy, 4);
    std::memcpy(&xyz[2], p + oz, 4);
    for (float v : xyz)
      if (!(std::abs(v) <= bounds::kMaxCoordinate))  // also NaN
        throw ParseError(file, where,
                         "coordinate " + bounds::numberText(v) + " m is not within " +
                             bounds::rangeText(-bounds::kMaxCoordinate, bounds::kMaxCoordinate));
    c.points[i] = Eigen::Vector3f(xyz[0], xyz[1], xyz[2]);
    if (ol >= 0) {
      uint32_t l;
      std::memcpy(&l, p + ol, 4);
      if (l >= uint32_t(kNumLidarClasses))
        throw ParseError(file, where + " label",
                         std::to_string(l) + " is no LiDAR class id (0.." +
                             std::to_string(kNumLidarClasses - 1) + ")");
      c.labels[i] = static_cast<uint8_t>(l);
    }
    if (oc >= 0) {
      float conf;
      std::memcpy(&conf, p + oc, 4);
      if (!(conf >= 0 && conf <= 1))
        throw ParseError(file, where + " confidence",
                         bounds::numberText(conf) + " is not within [0, 1]");
      c.confidence[i] = conf;
    }
  }
  return c;
}

}  // namespace mapfuse::io
