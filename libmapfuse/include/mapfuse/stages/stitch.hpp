#pragma once
/// @file Stage `stitch`: merges per-tile vector maps into one map (see tiling/stitch.hpp).
#include <filesystem>
#include <string>
#include <vector>

#include "mapfuse/core/vector_map.hpp"
#include "mapfuse/tiling/stitch.hpp"

namespace mapfuse::stages {

/// @brief Reads the grid from `tiles_json` (written by `tile`) and one vector map per tile;
/// each map's tile is the path component named like "tile_<ix>_<iy>". Writes `out_map`
/// (.cbor/.json), a GeoJSON beside it, stitch.config.json and stitch.summary.json.
/// @throws ParseError when a path names no tile, InputError on origin mismatch.
VectorMap runStitch(const std::filesystem::path& tiles_json, const std::vector<std::string>& maps,
                    const std::filesystem::path& out_map, const tiling::StitchParams& params);

/// @brief Tile of a path: the last component matching tile_<ix>_<iy> ("m" marks negatives).
tiling::TileKey tileOfPath(const std::filesystem::path& path);

}  // namespace mapfuse::stages
