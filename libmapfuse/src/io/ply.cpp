#include "mapfuse/io/ply.hpp"

#include <cmath>
#include <cstring>
#include <sstream>

#include "cloud_records.hpp"
#include "mapfuse/core/classes.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/bounds.hpp"

namespace mapfuse::io {
namespace {

int typeSize(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32")
    return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}

// One value of type T at p (unaligned; host order, little-endian on the supported machines).
template <class T>
double load(const char* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return static_cast<double>(v);
}

double readValue(const char* p, const std::string& t) {
  if (t == "float" || t == "float32") return load<float>(p);
  if (t == "double" || t == "float64") return load<double>(p);
  if (t == "uchar" || t == "uint8") return load<uint8_t>(p);
  if (t == "char" || t == "int8") return load<int8_t>(p);
  if (t == "ushort" || t == "uint16") return load<uint16_t>(p);
  if (t == "short" || t == "int16") return load<int16_t>(p);
  if (t == "uint" || t == "uint32") return load<uint32_t>(p);
  return load<int32_t>(p);
}

}  // namespace

void writePly(const std::filesystem::path& path, const LabeledCloud& cloud) {
  // Per-point values are named scalar_*: CloudCompare loads a vertex property as a scalar field
  // without asking only when its name contains "SCAL" (and shows it without the prefix), and
  // int32 / float are types every reader keeps (Open3D's tensor reader drops ushort).
  std::ostringstream h;
  h << "ply\nformat binary_little_endian 1.0\ncomment mapfuse semantic voxel map\n"
    << "comment scalar_label: mapfuse LiDAR class id 0-7 (docs/formats.md \"LiDAR classes\")\n"
    << "comment scalar_confidence: the voxel's class probability\n"
    << "comment scalar_semantic_kitti: SemanticKITTI semantic id of the class\n"
    << "element vertex " << cloud.size() << "\n"
    << "property float x\nproperty float y\nproperty float z\n"
    << "property uchar red\nproperty uchar green\nproperty uchar blue\n"
    << "property int scalar_label\nproperty float scalar_confidence\n"
    << "property int scalar_semantic_kitti\nend_header\n";
  writeCloudRecords(path, cloud, h.str(), 12 + 3 + 4 + 4 + 4, [&](std::size_t i, char* p) {
    std::memcpy(p, cloud.points[i].data(), 12);
    const auto col = lidarClassColor(static_cast<LidarClass>(cloud.labels[i]));
    p[12] = static_cast<char>(col[0]);
    p[13] = static_cast<char>(col[1]);
    p[14] = static_cast<char>(col[2]);
    const int32_t label = cloud.labels[i];
    std::memcpy(p + 15, &label, 4);
    std::memcpy(p + 19, &cloud.confidence[i], 4);
    const int32_t kitti = semanticKittiId(static_cast<LidarClass>(cloud.labels[i]));
    std::memcpy(p + 23, &kitti, 4);
  });
}

LabeledCloud readPly(const std::filesystem::path& path) {
  return parsePly(readBytes(path), path.string());
}

LabeledCloud parsePly(const std::string& bytes, const std::string& file) {
  const auto end = bytes.find("end_header\n");
  if (bytes.rfind("ply\n", 0) != 0 || end == std::string::npos)
    throw ParseError(file, "header", "not a PLY file (missing 'ply' or 'end_header')");
  std::istringstream hs(bytes.substr(0, end));
  std::string line;
  long long n = -1;
  bool in_vertex = false, has_format = false;
  struct Prop {
    std::string type, name;
    int64_t offset;
  };
  std::vector<Prop> props;
  int64_t stride = 0;
  while (std::getline(hs, line)) {
    std::istringstream ls(line);
    std::string kw;
    ls >> kw;
    if (kw == "format") {
      std::string fmt;
      ls >> fmt;
      if (fmt != "binary_little_endian")
        throw ParseError(file, "format", "'" + fmt + "' unsupported (binary_little_endian only)");
      has_format = true;
    } else if (kw == "element") {
      std::string name;
      ls >> name;
      const bool vertex = name == "vertex";
      if (vertex && n >= 0) throw ParseError(file, "element vertex", "given twice");
      in_vertex = vertex;
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
      stride += sz;  // at most 8 a property of a header shorter than the file: no overflow
      props.push_back(p);
    }
  }
  if (!has_format) throw ParseError(file, "format", "missing");
  if (n < 0) throw ParseError(file, "element vertex", "missing");
  auto findProp = [&](const std::string& name) -> const Prop* {
    for (const auto& p : props)
      if (p.name == name) return &p;
    return nullptr;
  };
  const Prop *px = findProp("x"), *py = findProp("y"), *pz = findProp("z");
  if (!px || !py || !pz) throw ParseError(file, "property x/y/z", "missing");
  // scalar_* since issue 35 (CloudCompare's convention); the plain names of earlier files too.
  const Prop* pl = findProp("scalar_label") ? findProp("scalar_label") : findProp("label");
  const Prop* pc =
      findProp("scalar_confidence") ? findProp("scalar_confidence") : findProp("confidence");
  const std::size_t body = end + std::strlen("end_header\n");
  const auto need = bounds::checkedMultiply(n, stride);
  if (!need || uint64_t(*need) > bytes.size() - body)
    throw ParseError(file, "vertex",
                     "body truncated: " + std::to_string(bytes.size() - body) + " bytes for " +
                         std::to_string(n) + " vertices of " + std::to_string(stride) + " bytes");
  LabeledCloud c;
  c.points.resize(static_cast<std::size_t>(n));
  c.labels.assign(static_cast<std::size_t>(n), 0);
  c.confidence.assign(static_cast<std::size_t>(n), 1.0f);
  for (std::size_t i = 0; i < c.points.size(); ++i) {
    const char* p = bytes.data() + body + i * static_cast<std::size_t>(stride);
    const std::string where = "vertex " + std::to_string(i);
    for (const Prop* axis : {px, py, pz}) {
      const double v = readValue(p + axis->offset, axis->type);
      if (!(std::abs(v) <= bounds::kMaxCoordinate))  // also NaN
        throw ParseError(file, where + " " + axis->name,
                         bounds::numberText(v) + " m is not within " +
                             bounds::rangeText(-bounds::kMaxCoordinate, bounds::kMaxCoordinate));
      c.points[i][axis == px ? 0 : axis == py ? 1 : 2] = static_cast<float>(v);
    }
    if (pl) {
      const double label = readValue(p + pl->offset, pl->type);
      if (!(label >= 0 && label < kNumLidarClasses && label == std::floor(label)))
        throw ParseError(file, where + " label",
                         bounds::numberText(label) + " is no LiDAR class id (0.." +
                             std::to_string(kNumLidarClasses - 1) + ")");
      c.labels[i] = static_cast<uint8_t>(label);
    }
    if (pc) {
      const double conf = readValue(p + pc->offset, pc->type);
      if (!(conf >= 0 && conf <= 1))
        throw ParseError(file, where + " confidence",
                         bounds::numberText(conf) + " is not within [0, 1]");
      c.confidence[i] = static_cast<float>(conf);
    }
  }
  return c;
}

}  // namespace mapfuse::io
