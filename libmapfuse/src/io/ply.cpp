#include "mapfuse/io/ply.hpp"

#include <cstring>
#include <sstream>

#include "mapfuse/core/classes.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/io/atomic_file.hpp"

namespace mapfuse::io {
namespace {

void checkCloud(const LabeledCloud& c, const std::string& what) {
  if (c.labels.size() != c.size() || c.confidence.size() != c.size())
    throw InputError(what + ": points, labels and confidence differ in size");
}

int typeSize(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32")
    return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}

double readValue(const char* p, const std::string& t) {
  if (t == "float" || t == "float32") {
    float f;
    std::memcpy(&f, p, 4);
    return f;
  }
  if (t == "double" || t == "float64") {
    double d;
    std::memcpy(&d, p, 8);
    return d;
  }
  if (t == "uchar" || t == "uint8") return static_cast<uint8_t>(*p);
  if (t == "char" || t == "int8") return static_cast<int8_t>(*p);
  if (t == "ushort" || t == "uint16") {
    uint16_t v;
    std::memcpy(&v, p, 2);
    return v;
  }
  if (t == "short" || t == "int16") {
    int16_t v;
    std::memcpy(&v, p, 2);
    return v;
  }
  if (t == "uint" || t == "uint32") {
    uint32_t v;
    std::memcpy(&v, p, 4);
    return v;
  }
  int32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

}  // namespace

void writePly(const std::filesystem::path& path, const LabeledCloud& cloud) {
  checkCloud(cloud, path.string());
  std::ostringstream h;
  h << "ply\nformat binary_little_endian 1.0\ncomment mapfuse semantic voxel map\n"
    << "comment label: mapfuse LiDAR class id 0-7 (docs/formats.md \"LiDAR classes\")\n"
    << "comment semantic_kitti: SemanticKITTI semantic id of the class\n"
    << "element vertex " << cloud.size() << "\n"
    << "property float x\nproperty float y\nproperty float z\n"
    << "property uchar red\nproperty uchar green\nproperty uchar blue\n"
    << "property uchar label\nproperty float confidence\nproperty ushort semantic_kitti\n"
    << "end_header\n";
  const std::string header = h.str();
  constexpr std::size_t kStride = 12 + 3 + 1 + 4 + 2;
  std::string body(cloud.size() * kStride, '\0');
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    char* p = body.data() + i * kStride;
    std::memcpy(p, cloud.points[i].data(), 12);
    const auto col = lidarClassColor(static_cast<LidarClass>(cloud.labels[i]));
    p[12] = static_cast<char>(col[0]);
    p[13] = static_cast<char>(col[1]);
    p[14] = static_cast<char>(col[2]);
    p[15] = static_cast<char>(cloud.labels[i]);
    std::memcpy(p + 16, &cloud.confidence[i], 4);
    const uint16_t kitti = semanticKittiId(static_cast<LidarClass>(cloud.labels[i]));
    std::memcpy(p + 20, &kitti, 2);
  }
  writeFileAtomic(path, [&](std::ostream& out) {
    out.write(header.data(), static_cast<std::streamsize>(header.size()));
    out.write(body.data(), static_cast<std::streamsize>(body.size()));
  });
}

LabeledCloud readPly(const std::filesystem::path& path) {
  const std::string bytes = readBytes(path);
  const std::string file = path.string();
  const auto end = bytes.find("end_header\n");
  if (bytes.rfind("ply\n", 0) != 0 || end == std::string::npos)
    throw ParseError(file, "header", "not a PLY file (missing 'ply' or 'end_header')");
  std::istringstream hs(bytes.substr(0, end));
  std::string line;
  long long n = -1;
  bool in_vertex = false;
  struct Prop {
    std::string type, name;
    int offset;
  };
  std::vector<Prop> props;
  int stride = 0;
  while (std::getline(hs, line)) {
    std::istringstream ls(line);
    std::string kw;
    ls >> kw;
    if (kw == "format") {
      std::string fmt;
      ls >> fmt;
      if (fmt != "binary_little_endian")
        throw ParseError(file, "format", "'" + fmt + "' unsupported (binary_little_endian only)");
    } else if (kw == "element") {
      std::string name;
      ls >> name;
      in_vertex = name == "vertex";
      if (in_vertex && !(ls >> n && n >= 0))
        throw ParseError(file, "element vertex", "bad vertex count");
      if (!in_vertex && n < 0)
        throw ParseError(file, "element " + name, "elements before 'vertex' are unsupported");
    } else if (kw == "property" && in_vertex) {
      Prop p;
      ls >> p.type >> p.name;
      if (p.type == "list") throw ParseError(file, "property", "list properties unsupported");
      const int sz = typeSize(p.type);
      if (sz == 0) throw ParseError(file, "property " + p.name, "unknown type '" + p.type + "'");
      p.offset = stride;
      stride += sz;
      props.push_back(p);
    }
  }
  if (n < 0) throw ParseError(file, "element vertex", "missing");
  auto findProp = [&](const std::string& name) -> const Prop* {
    for (const auto& p : props)
      if (p.name == name) return &p;
    return nullptr;
  };
  const Prop *px = findProp("x"), *py = findProp("y"), *pz = findProp("z");
  if (!px || !py || !pz) throw ParseError(file, "property x/y/z", "missing");
  const Prop* pl = findProp("label");
  const Prop* pc = findProp("confidence");
  const std::size_t body = end + std::strlen("end_header\n");
  if (bytes.size() - body < static_cast<std::size_t>(n) * stride)
    throw ParseError(file, "vertex",
                     "body truncated: " + std::to_string(bytes.size() - body) + " bytes for " +
                         std::to_string(n) + " vertices of " + std::to_string(stride));
  LabeledCloud c;
  c.points.resize(static_cast<std::size_t>(n));
  c.labels.assign(static_cast<std::size_t>(n), 0);
  c.confidence.assign(static_cast<std::size_t>(n), 1.0f);
  for (long long i = 0; i < n; ++i) {
    const char* p = bytes.data() + body + static_cast<std::size_t>(i) * stride;
    c.points[i] = Eigen::Vector3f(static_cast<float>(readValue(p + px->offset, px->type)),
                                  static_cast<float>(readValue(p + py->offset, py->type)),
                                  static_cast<float>(readValue(p + pz->offset, pz->type)));
    if (pl) c.labels[i] = static_cast<uint8_t>(readValue(p + pl->offset, pl->type));
    if (pc) c.confidence[i] = static_cast<float>(readValue(p + pc->offset, pc->type));
  }
  return c;
}

}  // namespace mapfuse::io
