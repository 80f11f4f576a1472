#pragma once
/// @file A polyline's points by horizontal grid cell, as index ranges: which points of a long
/// line lie near a place, in their order along it, without visiting the others. A solid lane line
/// is one observable piece however long; the simulator's observers (the LSM observer and the
/// frames writer) visit, per keyframe or frame, only its points near the vehicle.
#include <Eigen/Core>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "mapfuse/sim/polyline.hpp"

namespace mapfuse::sim {

class PointCells {
 public:
  PointCells() = default;
  /// @param cell m, the grid's cell size
  PointCells(const Polyline& points, double cell);
  /// @brief Indices, ascending, of the points in the cells that the square of half-side `radius`
  /// around `center` (xy) touches.
  std::vector<uint32_t> near(const Eigen::Vector3d& center, double radius) const;
  /// @brief Cell keys the points occupy (each once; voxel_grid::cellKey2d).
  std::vector<int64_t> cells() const;

 private:
  double cell_ = 10.0;
  /// per cell, the ranges [begin, end) of the indices of the points in it
  std::unordered_map<int64_t, std::vector<std::pair<uint32_t, uint32_t>>> ranges_;
};

}  // namespace mapfuse::sim
