#pragma once
/// @file Splitting georeferenced LSMs into per-tile LSMs (core + overlap margin), so that align
/// and aggregate run per tile, independently, on one machine or many.
#include <map>
#include <vector>

#include "mapfuse/core/lsm.hpp"
#include "mapfuse/tiling/tile_grid.hpp"

namespace mapfuse::tiling {

/// @brief Cuts one LSM (frame enu) into the tiles its keyframes touch.
/// A tile gets each maximal run of consecutive keyframes inside its margin rectangle with at
/// least `min_keyframes` keyframes, the elements anchored to them and the GPS fixes within the
/// run's time span (± `gps_slack` s). A drive that enters a tile twice yields two runs, named
/// "<drive_id>.run<k>". One LSM at a time, so that a batch is cut in the memory of one drive.
/// @throws InputError when the LSM is not in ENU.
std::map<TileKey, std::vector<Lsm>> splitLsm(const Lsm& lsm, const TileGrid& grid,
                                             int min_keyframes, double gps_slack = 1.0);

}  // namespace mapfuse::tiling
