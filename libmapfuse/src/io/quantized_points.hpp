#pragma once
// Compact coordinates of the CBOR vector map (docs/formats.md "Compact encoding"): a point list
// as one flat integer array in units of the map's coordinate quantum, the first point absolute
// and every next one as the difference to its predecessor (small integers: 1-3 CBOR bytes each
// instead of 5-9 for a float). A Bezier chain is stored as its 3n+1 control points, the end
// point shared by two segments once.
#include <optional>
#include <vector>

#include "mapfuse/core/vector_map.hpp"
#include "mapfuse/io/json_view.hpp"

namespace mapfuse::io {

/// Flat delta-coded integers of `points` (each coordinate rounded to the quantum q > 0).
Json quantizedPointsToJson(const std::vector<Eigen::Vector3d>& points, double q);

/// The inverse; fails on `v` (file, field, problem) when the array is not whole 3D points.
std::vector<Eigen::Vector3d> quantizedPointsFromJson(const JsonView& v, double q);

/// The chain's control points with shared end points once, or nullopt when two consecutive
/// segments do not share their end point after rounding to q (then the chain is written as is).
std::optional<std::vector<Eigen::Vector3d>> chainControlPoints(
    const std::vector<BezierSegment>& chain, double q);

/// Segments from 3n+1 control points; fails on `v` when the count is not 3n+1 with n >= 1.
std::vector<BezierSegment> chainFromControlPoints(const std::vector<Eigen::Vector3d>& points,
                                                  const JsonView& v);

}  // namespace mapfuse::io
