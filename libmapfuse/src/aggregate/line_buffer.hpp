#pragma once
/// @file The buffer polygon of a gently curving polyline, built directly: the stage-1 polygons
/// of lane instantiation (aggregate/lane_instantiation.cpp). boost::geometry::buffer builds the
/// same polygon as a union of per-segment pieces, ~10 us per lane piece, the largest single cost
/// of aggregate at 50 traversals; here it is two offset polylines.
#include <Eigen/Core>
#include <optional>
#include <vector>

namespace mapfuse::aggregate {

/// @brief The polygon boost::geometry::buffer gives for an open polyline with
/// distance_symmetric(width), side_straight, join_miter and end_flat: the left offset of the
/// line (a mitre point at every inner vertex) and the right offset reversed, as one ring (no
/// repeated closing vertex, counter-clockwise when the line runs along +x). nullopt when that
/// simple construction may differ from Boost's union: fewer than 2 points, a repeated point, a
/// turn above 45 deg, more than 120 deg of turning in all, or a segment shorter than the inner
/// corners cut from it; the caller then uses Boost.
std::optional<std::vector<Eigen::Vector2d>> mitreBuffer(const std::vector<Eigen::Vector2d>& line,
                                                        double width);

/// @brief Area of a simple ring (shoelace), m^2, positive.
double ringArea(const std::vector<Eigen::Vector2d>& ring);

}  // namespace mapfuse::aggregate
