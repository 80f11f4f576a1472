#pragma once
/// @file Grids that keep a map update's cost with the area the new drives cover, not with the
/// size of the map (docs/update.md "Cost"): map elements by the cells their bounding box (grown
/// by a reach) touches, and one drive's lane-line observation segments by cell.
#include <Eigen/Core>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "mapfuse/aggregate/observations.hpp"
#include "mapfuse/core/vector_map.hpp"

namespace mapfuse::update {

/// Map elements by grid cell: element e is listed in every cell its bounding box grown by
/// `reach` touches, so that near(p) holds every element within `reach` of p.
class ElementIndex {
 public:
  ElementIndex(const VectorMap& map, double reach, double cell = 25.0);
  /// @brief Indices of the elements whose grown box may hold p (a superset, sorted).
  const std::vector<std::size_t>& near(const Eigen::Vector3d& p) const;
  /// @brief Indices of the elements whose grown box meets the box [lo, hi] (sorted, unique).
  std::vector<std::size_t> within(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) const;

 private:
  double cell_;
  std::unordered_map<int64_t, std::vector<std::size_t>> cells_;
  std::vector<std::size_t> none_;
};

/// One drive's lane-line observations as segments by grid cell (cells of the search distance):
/// the sideways search of a map line's sample visits the 3 x 3 cells around it.
class SegmentIndex {
 public:
  struct Segment {
    Eigen::Vector2d a, b;
    bool dashed = false;
  };
  SegmentIndex() = default;
  SegmentIndex(const std::vector<const aggregate::Observation*>& lines, double search);
  /// @brief Calls f(segment) for each segment with an end or its middle within the 3 x 3 cells
  /// around p (segments are at most a few metres: LSM line points 0.75 m apart).
  template <class F>
  void visit(const Eigen::Vector3d& p, F&& f) const {
    if (cells_.empty()) return;
    const int64_t cx = cellOf(p.x()), cy = cellOf(p.y());
    for (int64_t dx = -1; dx <= 1; ++dx)
      for (int64_t dy = -1; dy <= 1; ++dy) {
        const auto it = cells_.find(key(cx + dx, cy + dy));
        if (it == cells_.end()) continue;
        for (const std::size_t i : it->second) f(segments_[i]);
      }
  }

 private:
  int64_t cellOf(double v) const;
  static int64_t key(int64_t ix, int64_t iy);
  double cell_ = 4.0;
  std::vector<Segment> segments_;
  std::unordered_map<int64_t, std::vector<std::size_t>> cells_;
};

}  // namespace mapfuse::update
