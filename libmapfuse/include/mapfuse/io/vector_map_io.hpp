#pragma once
/// @file Vector map files (docs/formats.md "Vector map"): format "mapfuse.vector_map",
/// version 1, ENU with an explicit origin, JSON or CBOR by extension. The GeoJSON export is
/// in geojson.hpp.
#include <filesystem>

#include "mapfuse/core/vector_map.hpp"
#include "mapfuse/io/json_view.hpp"

namespace mapfuse::io {

constexpr const char* kVectorMapFormat = "mapfuse.vector_map";
constexpr int kVectorMapVersion = 1;

/// Options of the native writer.
struct VectorMapWriteOptions {
  /// Omit the sampled "points" of lane lines that have a Bezier chain; readers re-sample the
  /// chain (kBezierSampleStep). Keeps CBOR maps small.
  bool compact = false;
  /// Round coordinates to this many metres (0 = keep full precision).
  double coordinate_quantum = 0.0;
};

/// Spacing (m) at which readers sample a Bezier chain into "points" when a file omits them.
constexpr double kBezierSampleStep = 0.5;

Json vectorMapToJson(const VectorMap& map, const VectorMapWriteOptions& options = {});
VectorMap vectorMapFromJson(const Json& doc, const std::string& file);

VectorMap readVectorMap(const std::filesystem::path& path);
void writeVectorMap(const std::filesystem::path& path, const VectorMap& map,
                    const VectorMapWriteOptions& options = {});

/// @brief Point of a cubic Bezier segment at parameter s in [0, 1].
Eigen::Vector3d bezierPoint(const BezierSegment& b, double s);
/// @brief Samples a Bezier chain at roughly `step` metres (end points included).
std::vector<Eigen::Vector3d> sampleBezierChain(const std::vector<BezierSegment>& chain,
                                               double step);

}  // namespace mapfuse::io
