#pragma once
/// @file The updated map of a map update (docs/update.md "The updated map"): the existing map
/// with the detected changes applied. Unchanged elements are copied as read (id, geometry,
/// support, version); moved, re-striped and re-typed ones keep their id, take the after state
/// and their version + 1; removed ones leave the map (the change report lists them); added ones
/// are appended with the ids the detection gave them (above the map's largest), version 1.
#include <cstdint>
#include <vector>

#include "mapfuse/core/map_changes.hpp"
#include "mapfuse/core/vector_map.hpp"

namespace mapfuse::update {

struct UpdatedMap {
  VectorMap map;
  std::vector<int64_t> unchanged, changed, removed, added;  ///< ids by what happened to them
};

/// @brief `map` with `changes` (ids of `map`; at most one change per element) applied.
/// @throws InputError when a change names an element the map does not have, or one element twice.
UpdatedMap applyChanges(const VectorMap& map, const MapChanges& changes);

}  // namespace mapfuse::update
