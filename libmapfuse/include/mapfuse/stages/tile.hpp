#pragma once
/// @file Stage `tile`: cuts georeferenced LSMs into per-tile LSM sets (see tiling/split.hpp).
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mapfuse/core/param.hpp"

namespace mapfuse::stages {

struct TileParams {
  static constexpr const char* kName = "TileParams";
  double tile_size = 500.0;     ///< m, edge of a tile core
  double margin = 50.0;         ///< m, overlap added on every side
  int min_keyframes = 3;        ///< runs with fewer keyframes in a tile are left out
  std::string format = "cbor";  ///< per-tile LSM encoding: cbor | json

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("tile_size", tile_size, "m", "edge length of a tile core", gt(0) & le(1e6));
    v("margin", margin, "m", "overlap margin added on every side of a tile", in(0, 1e5));
    v.relation("margin", margin, margin < tile_size / 2, "< tile_size / 2");
    v("min_keyframes", min_keyframes, "", "runs with fewer keyframes in a tile are left out",
      in(2, 1000000));
    v("format", format, "", "per-tile LSM encoding: cbor or json", oneOf({"cbor", "json"}));
  }
};

/// @brief Reads LSMs (frame enu, one origin), writes <out>/<tile>/<drive>.<format> per tile and
/// <out>/tiles.json (grid, origin, tiles with core bounds and files), plus tile.config.json and
/// tile.summary.json. @return the tiles.json document.
nlohmann::json runTile(const std::vector<std::string>& lsm_files, const std::filesystem::path& out,
                       const TileParams& params);

}  // namespace mapfuse::stages
