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

/// @brief Strict parse. Names and index pairs are unique; a name or LSM path that could leave
/// the manifest's folder (absolute, "..", empty parts) is refused.
/// @throws ParseError naming `file` and the field.
TilesManifest tilesManifestFromJson(const Json& doc, const std::string& file);

/// @brief Reads and parses a tiles.json. @throws IoError, ParseError.
TilesManifest readTilesManifest(const std::filesystem::path& path);

}  // namespace mapfuse::io
