#pragma once
/// @file The tiled run's manifest `tiles.json` (docs/formats.md "Tiled runs", format
/// "mapfuse.tiles", version 1), written by `tile`, read by `balance` and `stitch`.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "mapfuse/geo/origin.hpp"
#include "mapfuse/io/json_view.hpp"

namespace mapfuse::io {

/// One tile of the manifest.
struct TilesManifestTile {
  std::string name;               ///< folder name, one safe path component ("tile_3_m1")
  int64_t ix = 0, iy = 0;         ///< grid indices, |ix| * tile_size within bounds::kMaxCoordinate
  std::vector<std::string> lsms;  ///< LSM files relative to the manifest's folder
};

struct TilesManifest {
  double tile_size = 0.0;  ///< m, within [1, bounds::kMaxCoordinate]
  double margin = 0.0;     ///< m, within [0, tile_size / 2)
  std::optional<geo::GeoOrigin> origin;
  std::vector<TilesManifestTile> tiles;
};

/// Relative tolerance of a tile's `core` against the grid (tile writes it from the same doubles).
inline constexpr double kCoreTolerance = 1e-9;

/// @brief Strict parse. Names and index pairs are unique; a name or LSM path that could leave
/// the manifest's folder (absolute, "..", empty parts) is refused.
/// @throws ParseError naming `file` and the field.
TilesManifest tilesManifestFromJson(const Json& doc, const std::string& file);

/// @brief Reads and parses a tiles.json. @throws IoError, ParseError.
TilesManifest readTilesManifest(const std::filesystem::path& path);

/// @brief For each of `maps` (one per tile, e.g. <tiles>/<tile>/aggregate/map.cbor), the index
/// in `manifest.tiles` of the tile it belongs to: the last path component that names a tile.
/// Every tile must have exactly one map: a map of no listed tile, two maps of one tile (or the
/// same map twice) and a tile without a map are refused.
/// @throws ConfigError (exit 2: the command line names the wrong set) naming `tiles_json` and
/// the map or tile.
std::vector<std::size_t> tileOfEachMap(const TilesManifest& manifest, const std::string& tiles_json,
                                       const std::vector<std::string>& maps);

}  // namespace mapfuse::io
