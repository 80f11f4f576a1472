#include "mapfuse/io/pcd.hpp"

#include <cstring>
#include <sstream>
#include <vector>

#include "mapfuse/core/classes.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/io/atomic_file.hpp"

namespace mapfuse::io {

void writePcd(const std::filesystem::path& path, const LabeledCloud& cloud) {
  if (cloud.labels.size() != cloud.size() || cloud.confidence.size() != cloud.size())
    throw InputError(path.string() + ": points, labels and confidence differ in size");
  std::ostringstream h;
  h << "# .PCD v0.7 - Point Cloud Data file format\n"
    << "# label: mapfuse LiDAR class id 0-7 (docs/formats.md \"LiDAR classes\")\n"
    << "# semantic_kitti: SemanticKITTI semantic id of the class\nVERSION 0.7\n"
    << "FIELDS x y z rgb label confidence semantic_kitti\nSIZE 4 4 4 4 4 4 4\n"
    << "TYPE F F F U U F U\nCOUNT 1 1 1 1 1 1 1\nWIDTH " << cloud.size() << "\nHEIGHT 1\n"
    << "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << cloud.size() << "\nDATA binary\n";
  const std::string header = h.str();
  constexpr std::size_t kStride = 28;
  std::string body(cloud.size() * kStride, '\0');
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    char* p = body.data() + i * kStride;
    std::memcpy(p, cloud.points[i].data(), 12);
    const auto col = lidarClassColor(static_cast<LidarClass>(cloud.labels[i]));
    const uint32_t rgb = (uint32_t{col[0]} << 16) | (uint32_t{col[1]} << 8) | col[2];
    const uint32_t label = cloud.labels[i];
    std::memcpy(p + 12, &rgb, 4);
    std::memcpy(p + 16, &label, 4);
    std::memcpy(p + 20, &cloud.confidence[i], 4);
    const uint32_t kitti = semanticKittiId(static_cast<LidarClass>(cloud.labels[i]));
    std::memcpy(p + 24, &kitti, 4);
  }
  writeFileAtomic(path, [&](std::ostream& out) {
    out.write(header.data(), static_cast<std::streamsize>(header.size()));
    out.write(body.data(), static_cast<std::streamsize>(body.size()));
  });
}

LabeledCloud readPcd(const std::filesystem::path& path) {
  const std::string bytes = readBytes(path);
  const std::string file = path.string();
  std::vector<std::string> fields, types;
  std::vector<int> sizes, counts;
  long long points = -1;
  std::size_t pos = 0;
  bool data = false;
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
      while (ls >> tok) sizes.push_back(std::atoi(tok.c_str()));
    } else if (kw == "TYPE") {
      while (ls >> tok) types.push_back(tok);
    } else if (kw == "COUNT") {
      while (ls >> tok) counts.push_back(std::atoi(tok.c_str()));
    } else if (kw == "POINTS") {
      if (!(ls >> points) || points < 0) throw ParseError(file, "POINTS", "bad count");
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
  int stride = 0;
  int ox = -1, oy = -1, oz = -1, ol = -1, oc = -1;
  std::string tl;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const std::string& f = fields[i];
    if ((f == "x" || f == "y" || f == "z" || f == "confidence") &&
        (sizes[i] != 4 || types[i] != "F"))
      throw ParseError(file, f, "must be SIZE 4 TYPE F");
    if (f == "x") ox = stride;
    if (f == "y") oy = stride;
    if (f == "z") oz = stride;
    if (f == "confidence") oc = stride;
    if (f == "label") {
      if (sizes[i] != 4) throw ParseError(file, "label", "must be SIZE 4");
      ol = stride;
    }
    stride += sizes[i] * counts[i];
  }
  if (ox < 0 || oy < 0 || oz < 0) throw ParseError(file, "FIELDS", "x, y, z missing");
  if (bytes.size() - pos < static_cast<std::size_t>(points) * stride)
    throw ParseError(file, "DATA", "body truncated");
  LabeledCloud c;
  c.points.resize(static_cast<std::size_t>(points));
  c.labels.assign(c.points.size(), 0);
  c.confidence.assign(c.points.size(), 1.0f);
  for (std::size_t i = 0; i < c.points.size(); ++i) {
    const char* p = bytes.data() + pos + i * stride;
    float x, y, z;
    std::memcpy(&x, p + ox, 4);
    std::memcpy(&y, p + oy, 4);
    std::memcpy(&z, p + oz, 4);
    c.points[i] = Eigen::Vector3f(x, y, z);
    if (ol >= 0) {
      uint32_t l;
      std::memcpy(&l, p + ol, 4);
      c.labels[i] = static_cast<uint8_t>(l);
    }
    if (oc >= 0) std::memcpy(&c.confidence[i], p + oc, 4);
  }
  return c;
}

}  // namespace mapfuse::io
