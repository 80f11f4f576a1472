#pragma once
/// @file The vector HD map (DESIGN.md "The vector map"): instances with stable ids in the
/// ENU frame of an explicit origin. The simulator's ground truth uses the same type.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "mapfuse/core/classes.hpp"
#include "mapfuse/core/lat_lon_alt.hpp"

namespace mapfuse {

/// One cubic Bezier segment: control points P0..P3 in ENU (m). Consecutive segments of a chain
/// share end points (P3 of one is P0 of the next).
using BezierSegment = std::array<Eigen::Vector3d, 4>;

/// How many drives and observations formed an instance.
struct Support {
  int drives = 0;
  int observations = 0;
};

struct MapInstance {
  int64_t id = 0;  ///< stable id
  CrowdClass cls = CrowdClass::kLaneLine;
  Attributes attributes;
  /// Geometry in ENU (m), read by geometryKind(cls): kLine -> sampled polyline;
  /// kPlanar -> polygon ring (not closed; an oriented rectangle has 4 corners);
  /// kPoint -> one point (the base).
  std::vector<Eigen::Vector3d> points;
  std::vector<BezierSegment> bezier;  ///< lane lines: the fitted chain (may be empty)
  double height = 0.0;                ///< m; poles, lights: vertical extent above the base
  Support support;
  std::vector<int64_t> source_ids;  ///< provenance (truth ids, or ids of merged elements)
  int version = 1;  ///< 1 as built; a map update that changes the element adds 1 (docs/update.md)
  std::string note;                 ///< free text, e.g. "placed by simulator"
};

struct VectorMap {
  geo::GeoOrigin origin;  ///< required: ENU origin of every coordinate
  std::string source;     ///< who made it ("aggregate", "simulate ground truth", ...)
  std::vector<MapInstance> instances;
};

/// @brief Length of a polyline (m).
double polylineLength(const std::vector<Eigen::Vector3d>& points);

/// @brief Centre of an instance (ENU, m): of a line, the centroid along its length (vertices
/// crowded at one place do not pull it: a stitched or scope-cut stop line); of a polygon or
/// point, the mean of its vertices.
Eigen::Vector3d instanceCentre(const MapInstance& inst);

/// @brief Total length of the line instances of a map (m), e.g. for KB/km.
double totalLineLength(const VectorMap& map, CrowdClass cls);

/// @brief Checks finite geometry, unique ids, point counts per geometry kind.
/// @throws InputError naming `source` and the problem.
void validateVectorMap(const VectorMap& map, const std::string& source);

}  // namespace mapfuse
