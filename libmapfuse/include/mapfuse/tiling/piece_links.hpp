#pragma once
/// @file Which drive pieces of one tile align tied together: pieces whose elements coincide after
/// alignment (whether the pose graph or GBA put them there), found by a voxel index per class.
/// `balance` moves such pieces as one registration group, so that it never pulls apart what a
/// tile's align made agree.
#include <utility>
#include <vector>

#include "mapfuse/core/lsm.hpp"

namespace mapfuse::tiling {

/// @brief Pairs (a, b), a < b, of LSMs (frame enu) of which at least `min_points` element
/// points of one lie within `distance` (m) of an element point of the same class of the other.
std::vector<std::pair<int, int>> agreeingPieces(const std::vector<Lsm>& aligned, double distance,
                                                int min_points);

}  // namespace mapfuse::tiling
