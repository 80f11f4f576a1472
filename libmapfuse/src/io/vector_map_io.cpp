#include "mapfuse/io/vector_map_io.hpp"

#include <cmath>
#include <optional>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/json_geometry.hpp"
#include "quantized_points.hpp"

namespace mapfuse::io {
namespace {

Eigen::Vector3d quantize(const Eigen::Vector3d& p, double q) {
  if (q <= 0.0) return p;
  return (p / q).array().round().matrix() * q;
}

Json instanceToJson(const MapInstance& inst, const VectorMapWriteOptions& opt) {
  Json j = {{"id", inst.id}};
  writeClassAndAttributes(j, inst.cls, inst.attributes);
  const bool omit_points = opt.compact && !inst.bezier.empty();
  const double q = opt.coordinate_quantum;
  const bool integers = opt.compact && q > 0;  // compact encoding (quantized_points.hpp)
  if (!omit_points && integers) {
    j["points_q"] = quantizedPointsToJson(inst.points, q);
  } else if (!omit_points) {
    Json pts = Json::array();
    for (const auto& p : inst.points) pts.push_back(vec3ToJson(quantize(p, q)));
    j["points"] = std::move(pts);
  }
  const auto control = integers ? chainControlPoints(inst.bezier, q) : std::nullopt;
  if (!inst.bezier.empty() && control) {
    j["bezier_q"] = quantizedPointsToJson(*control, q);
  } else if (!inst.bezier.empty()) {
    Json chain = Json::array();
    for (const auto& seg : inst.bezier) {
      Json s = Json::array();
      for (const auto& c : seg) s.push_back(vec3ToJson(quantize(c, opt.coordinate_quantum)));
      chain.push_back(std::move(s));
    }
    j["bezier"] = std::move(chain);
  }
  if (inst.height != 0.0) j["height"] = inst.height;
  j["support"] = {{"drives", inst.support.drives}, {"observations", inst.support.observations}};
  if (!inst.source_ids.empty()) j["source_ids"] = inst.source_ids;
  if (!inst.note.empty()) j["note"] = inst.note;
  if (inst.version != 1) j["version"] = inst.version;  // absent: 1 (maps before updates)
  return j;
}

/// The map's quantum, required by the compact keys.
double quantumFor(const JsonView& field, std::optional<double> quantum) {
  if (!quantum) field.fail("integer coordinates need the map's top-level 'quantum'");
  return *quantum;
}

/// Sum of the control-polygon lengths of a chain (>= its arc length), m.
double chainLength(const std::vector<BezierSegment>& chain) {
  double length = 0.0;
  for (const auto& seg : chain)
    length += (seg[1] - seg[0]).norm() + (seg[2] - seg[1]).norm() + (seg[3] - seg[2]).norm();
  return length;
}

/// Bounds the points a reader samples from Bezier chains: per chain and per document.
void checkChainLength(const JsonView& field, const std::vector<BezierSegment>& chain,
                      double& document_total) {
  const double length = chainLength(chain);
  if (length > bounds::kMaxChainLength)
    field.fail("Bezier chain is " + bounds::numberText(length) + " m long, more than " +
               bounds::numberText(bounds::kMaxChainLength) + " m");
  document_total += length;
  if (document_total > bounds::kMaxChainLengthPerDocument)
    field.fail("the document's Bezier chains exceed " +
               bounds::numberText(bounds::kMaxChainLengthPerDocument) + " m in total");
}

MapInstance instanceFromJson(const JsonView& v, std::optional<double> quantum,
                             double& chain_total) {
  v.onlyKeys({"id", "class", "style", "color", "points", "points_q", "bezier", "bezier_q", "height",
              "support", "source_ids", "note", "version"});
  MapInstance inst;
  inst.id = v.at("id").integer();
  readClassAndAttributes(v, inst.cls, inst.attributes);
  if (auto b = v.find("bezier_q")) {
    const double q = quantumFor(*b, quantum);
    inst.bezier = chainFromControlPoints(quantizedPointsFromJson(*b, q), *b);
    checkChainLength(*b, inst.bezier, chain_total);
  } else if (auto b = v.find("bezier")) {
    for (std::size_t i = 0; i < b->size(); ++i) {
      const JsonView seg = b->at(i);
      if (seg.size() != 4) seg.fail("a cubic Bezier segment needs 4 control points");
      BezierSegment s;
      for (int k = 0; k < 4; ++k) s[k] = seg.at(k).coordinate();
      inst.bezier.push_back(s);
    }
    checkChainLength(*b, inst.bezier, chain_total);
  }
  if (!inst.bezier.empty() && geometryKind(inst.cls) != GeometryKind::kLine)
    v.at("class").fail("a Bezier chain belongs to a line class, not '" +
                       std::string(crowdClassName(inst.cls)) + "'");
  if (auto p = v.find("points_q"))
    inst.points = quantizedPointsFromJson(*p, quantumFor(*p, quantum));
  else if (auto p = v.find("points"))
    inst.points = readPoints(*p);
  else if (!inst.bezier.empty())
    inst.points = sampleBezierChain(inst.bezier, kBezierSampleStep);
  else
    v.at("points");  // throws: geometry missing
  if (auto h = v.find("height")) inst.height = h->number(0.0, bounds::kMaxElementHeight);
  if (auto s = v.find("support")) {
    s->onlyKeys({"drives", "observations"});
    inst.support.drives = s->at("drives").integerInt(0);
    inst.support.observations = s->at("observations").integerInt(0);
  }
  if (auto ids = v.find("source_ids"))
    for (std::size_t i = 0; i < ids->size(); ++i) inst.source_ids.push_back(ids->at(i).integer());
  if (auto n = v.find("note")) inst.note = n->string();
  if (auto ver = v.find("version")) inst.version = ver->integerInt(1);
  return inst;
}

}  // namespace

Eigen::Vector3d bezierPoint(const BezierSegment& b, double s) {
  const double u = 1.0 - s;
  return u * u * u * b[0] + 3 * u * u * s * b[1] + 3 * u * s * s * b[2] + s * s * s * b[3];
}

std::vector<Eigen::Vector3d> sampleBezierChain(const std::vector<BezierSegment>& chain,
                                               double step) {
  std::vector<Eigen::Vector3d> out;
  for (const auto& seg : chain) {
    const double chord =
        (seg[1] - seg[0]).norm() + (seg[2] - seg[1]).norm() + (seg[3] - seg[2]).norm();
    // Readers bound chains to bounds::kMaxChainLength; the guard keeps the count exact.
    const double count = std::ceil(chord / step);
    if (!(count <= 1e9))
      throw InputError("Bezier segment too long to sample every " + bounds::numberText(step) +
                       " m");
    const int n = std::max(1, int(count));
    for (int i = out.empty() ? 0 : 1; i <= n; ++i) out.push_back(bezierPoint(seg, double(i) / n));
  }
  return out;
}

Json vectorMapToJson(const VectorMap& map, const VectorMapWriteOptions& options) {
  Json inst = Json::array();
  for (const auto& i : map.instances) inst.push_back(instanceToJson(i, options));
  Json doc = {{"format", kVectorMapFormat},
              {"version", kVectorMapVersion},
              {"source", map.source},
              {"origin", originToJson(map.origin)},
              {"instances", std::move(inst)}};
  if (options.compact && options.coordinate_quantum > 0)
    doc["quantum"] = options.coordinate_quantum;
  return doc;
}

VectorMap vectorMapFromJson(const Json& doc, const std::string& file) {
  const JsonView v(doc, file);
  v.onlyKeys({"format", "version", "source", "origin", "quantum", "instances"});
  v.checkFormat(kVectorMapFormat, kVectorMapVersion);
  VectorMap map;
  if (auto s = v.find("source")) map.source = s->string();
  map.origin = readOrigin(v.at("origin"));
  std::optional<double> quantum;
  if (auto q = v.find("quantum")) quantum = q->number(bounds::kMinQuantum, bounds::kMaxQuantum);
  const JsonView inst = v.at("instances");
  double chain_total = 0.0;
  for (std::size_t i = 0; i < inst.size(); ++i)
    map.instances.push_back(instanceFromJson(inst.at(i), quantum, chain_total));
  validateVectorMap(map, file);
  return map;
}

VectorMap readVectorMap(const std::filesystem::path& path) {
  return vectorMapFromJson(readDocument(path), path.string());
}

void writeVectorMap(const std::filesystem::path& path, const VectorMap& map,
                    const VectorMapWriteOptions& options) {
  writeDocument(path, vectorMapToJson(map, options));
}

}  // namespace mapfuse::io
