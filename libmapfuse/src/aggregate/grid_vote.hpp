#pragma once
/// @file The grid-vote baseline of Qin et al. 2021 ("A Light-Weight Semantic Map Production
/// System for Autonomous Driving"), used by `aggregate --method grid_vote` for the Table 3
/// comparison of Song et al. 2023: every aligned ground observation (lane line, stop line, ground
/// arrow, crosswalk: the road markings that system maps) is painted into square cells of
/// `cell_size` (0.1 m) in the EN plane, each cell counting one vote per drive and class;
/// a cell takes the class with the most votes when it has at least `min_votes`. The grid is
/// sparse (a hash map of the painted cells): memory grows with the painted area, not with the
/// extent of the world. Vectorisation of the voted cells: grid_instances.cpp.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

#include "mapfuse/aggregate/observations.hpp"
#include "mapfuse/aggregate/settings.hpp"
#include "mapfuse/core/voxel_grid.hpp"

namespace mapfuse::aggregate {

/// The classes grid voting maps: CrowdClass values 0 .. kNumGridClasses - 1 (lane_line,
/// stop_line, ground_arrow, crosswalk).
constexpr int kNumGridClasses = 4;

/// @brief True for the ground classes grid voting maps.
inline bool isGridClass(CrowdClass c) {
  return int(c) < kNumGridClasses;
}

/// One cell of the grid. Counts saturate at 65535.
struct GridCell {
  std::array<uint16_t, kNumGridClasses> votes{};  ///< per class, one per drive
  std::array<uint16_t, 3> style{};                ///< lane-line votes per LineStyle
  std::array<uint16_t, 3> color{};                ///< lane-line votes per LineColor
  float z_sum = 0;                                ///< m, sum of the voters' heights at the cell
};

/// One cell an observation paints.
struct PaintedCell {
  int64_t key = 0;  ///< VoteGrid::key
  float z = 0;      ///< m, the observation's height there
  CrowdClass cls = CrowdClass::kLaneLine;
  Attributes attributes;
};

/// The sparse voting grid: cell (ix, iy) covers [ix, ix + 1) x [iy, iy + 1) * cell_size.
class VoteGrid {
 public:
  explicit VoteGrid(double cell_size) : cell_(cell_size) {}

  /// @brief Appends the cells one observation paints to `out`: lines (lane and stop lines) as
  /// strokes of `line_width` (at least the cells their centreline passes within half a cell
  /// of), ground polygons (arrows, crosswalks) filled (the cells whose centre lies inside).
  /// Elements of the other classes paint nothing.
  void paint(const Observation& o, double line_width, std::vector<PaintedCell>& out) const;

  /// @brief Casts one drive's votes: one per painted cell and class, however many of the
  /// drive's observations painted it (a vehicle that saw a marking in many frames, or stood
  /// before it, counts once). Sorts `painted`.
  void vote(std::vector<PaintedCell>& painted);

  /// @brief Upper bound of the cells paint() appends for `o` (the budget check of voteGrid).
  double cellsBound(const Observation& o, double line_width) const;

  /// @brief The class of the most votes when it has at least min_votes (ties: the lower class).
  static std::optional<CrowdClass> winner(const GridCell& cell, int min_votes);

  /// @brief Centre of cell `key` in ENU, z the mean height of its votes.
  Eigen::Vector3d centre(int64_t key) const;

  static int64_t key(int64_t ix, int64_t iy) { return voxel_grid::cellKey2d(ix, iy); }
  static int64_t ix(int64_t key) { return int32_t(uint64_t(key) >> 32); }
  static int64_t iy(int64_t key) { return int32_t(uint32_t(uint64_t(key) & 0xffffffffULL)); }

  double cellSize() const { return cell_; }
  const std::unordered_map<int64_t, GridCell>& cells() const { return cells_; }
  std::size_t votes() const { return votes_; }  ///< votes cast so far

 private:
  double cell_;
  std::unordered_map<int64_t, GridCell> cells_;
  std::size_t votes_ = 0;
};

/// @brief Paints the ground observations `indices` of `items` into a grid of p.cell_size, one
/// vote per drive, cell and class.
/// @throws InputError when the observations would paint more cells than the budget (64k per
/// observation on average, at least 4e6 in all), naming the largest element and its LSM.
VoteGrid voteGrid(const std::vector<Observation>& items, const std::vector<std::size_t>& indices,
                  const GridVoteParams& p);

}  // namespace mapfuse::aggregate
