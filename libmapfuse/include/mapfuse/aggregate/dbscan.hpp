#pragma once
/// @file DBSCAN (Ester et al. 1996) over an abstract neighbourhood, as used twice by §4.3 of
/// Song et al. 2023. Deterministic: objects are visited in index order.
#include <cstddef>
#include <functional>
#include <vector>

namespace mapfuse::aggregate {

struct DbscanResult {
  std::vector<int> labels;  ///< cluster id per object (0..num_clusters-1), -1 = noise
  int num_clusters = 0;
  int num_noise = 0;
};

/// Neighbours of object i within eps, NOT including i itself.
using NeighbourFn = std::function<std::vector<std::size_t>(std::size_t i)>;

/// @brief Classic DBSCAN: i is a core object when |N_eps(i)| >= min_pts, where N_eps(i)
/// counts i itself; clusters are the density-connected sets; objects reached by no core object
/// are noise.
/// @param n number of objects. @param min_pts MinPts (>= 1).
/// @param neighbours eps-neighbourhood query (may be called more than once per object).
DbscanResult dbscan(std::size_t n, int min_pts, const NeighbourFn& neighbours);

/// @brief DBSCAN on precomputed neighbour lists (each without the object itself).
DbscanResult dbscan(const std::vector<std::vector<std::size_t>>& neighbour_lists, int min_pts);

}  // namespace mapfuse::aggregate
