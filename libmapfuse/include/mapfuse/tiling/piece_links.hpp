#pragma once
/// @file Which drive pieces of one tile align tied together: pieces whose elements coincide after
/// alignment (whether the pose graph or GBA put them there), found by a voxel index per class.
/// `balance` moves such pieces as one registration group, so that it never pulls apart what a
/// tile's align made agree.
#include <utility>
#include <vector>

#include "mapfuse/core/lsm.hpp"
#include "mapfuse/core/param.hpp"

namespace mapfuse::tiling {

/// When two aligned pieces count as tied together.
struct PieceLinkSettings {
  double link_distance = 0.3;  ///< m: element points of two pieces this close coincide
  int link_min_points = 10;    ///< coinciding points that make two pieces one group

  template <class V>
  void visit(V& v) {
    v("link_distance", link_distance, "m",
      "element points of two aligned pieces this close coincide (tiling/piece_links.hpp)",
      param::gt(0) & param::le(100));
    v("link_min_points", link_min_points, "",
      "coinciding element points that put two pieces of a tile in one group",
      param::in(1, 1000000));
  }
};

/// @brief Pairs (a, b), a < b, of LSMs (frame enu) of which at least `min_points` element
/// points of one lie within `distance` (m) of an element point of the same class of the other.
std::vector<std::pair<int, int>> agreeingPieces(const std::vector<Lsm>& aligned, double distance,
                                                int min_points);

}  // namespace mapfuse::tiling
