#pragma once
/// @file What balance's placement did, for a reader of its summary: the groups moved most
/// (where tiles disagreed most) and, per tile, its groups and the move of its largest one
/// (most of the tile's map).
#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mapfuse/tiling/placement.hpp"

namespace mapfuse::tiling {

/// One group of pieces and its move.
struct GroupShift {
  GroupKey group;
  int pieces = 0;                                   ///< drive pieces in the group
  Eigen::Vector3d shift = Eigen::Vector3d::Zero();  ///< m, ENU
};

/// One tile: how many groups it holds and the move of its largest.
struct TileShift {
  std::string tile;  ///< tile name
  int groups = 0;
  GroupShift largest;
};

struct PlacementOverview {
  std::vector<GroupShift> largest_shifts;  ///< by horizontal move, largest first
  int single_piece_groups = 0;             ///< groups of one piece (nothing tied it to others)
  std::vector<TileShift> per_tile;         ///< in tile-name order
};

/// @brief The overview of `shifts` (solvePlacement's result) over groups of `group_size`
/// pieces; `count` largest moves are listed.
PlacementOverview overviewOfShifts(const std::map<GroupKey, Eigen::Vector3d>& shifts,
                                   const std::map<GroupKey, int>& group_size, std::size_t count);

/// @brief balance.summary.json's account of the placement (docs/tiling.md): the report's counts
/// and residual, the largest group moves and the per-tile overview.
nlohmann::json placementSummary(const PlacementReport& report, const PlacementOverview& overview);

}  // namespace mapfuse::tiling
