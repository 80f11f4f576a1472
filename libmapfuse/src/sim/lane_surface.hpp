#pragma once
/// @file The road surface of a map world, fitted to its lanes (issue 33: a vehicle rolls with the
/// road's cross-slope, superelevation and banking included). OpenDRIVE lanes carry the road's
/// superelevation in their heights (z = elevation + t sin(roll)) and Lanelet2 lanes their bounds'
/// heights; the true lane lines mark both edges of every lane. The surface at (x, y) is the
/// least-squares plane through the lane centreline and lane-line samples within kRadius m whose
/// height is within kDeckGap m of the query's z (a bridge above or a road below is another
/// deck); with too few samples, or samples along one line only (no extent across), the mean
/// height of the samples (level across), or the query's own z when there are none.
#include <Eigen/Core>
#include <functional>

#include "mapfuse/sim/world.hpp"

namespace mapfuse::sim {

/// @brief World::surface_height for a world built from a map (sim/map_world.cpp).
std::function<double(const Eigen::Vector3d&)> laneSurface(const World& world);

}  // namespace mapfuse::sim
