#include <filesystem>
#include <map>
#include <optional>
#include <system_error>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/tiles_manifest.hpp"

namespace mapfuse::io {

namespace {
std::string resolved(const std::string& p) {
  std::error_code ec;
  auto r = std::filesystem::weakly_canonical(std::filesystem::absolute(p), ec);
  return ec ? p : r.string();
}
}  // namespace

std::vector<std::size_t> tileOfEachMap(const TilesManifest& manifest, const std::string& tiles_json,
                                       const std::vector<std::string>& maps) {
  std::map<std::string, std::size_t> by_name;
  for (std::size_t i = 0; i < manifest.tiles.size(); ++i) by_name[manifest.tiles[i].name] = i;
  std::vector<std::size_t> tile_of;
  std::map<std::size_t, std::string> map_of;  // tile index -> its map
  std::map<std::string, std::string> seen;    // resolved path -> as given
  for (const auto& m : maps) {
    const auto [it, fresh] = seen.emplace(resolved(m), m);
    if (!fresh) throw ConfigError(m + ": the same map as " + it->second + " (given twice)");
    std::optional<std::size_t> tile;
    for (const auto& part : std::filesystem::path(m))
      if (auto t = by_name.find(part.string()); t != by_name.end()) tile = t->second;
    if (!tile)
      throw ConfigError(m + ": no folder of the path names a tile of " + tiles_json +
                        " (maps are <tile>/.../map.cbor)");
    if (auto [prev, ok] = map_of.emplace(*tile, m); !ok)
      throw ConfigError(m + ": a second map of tile '" + manifest.tiles[*tile].name + "' of " +
                        tiles_json + " (the first: " + prev->second + ")");
    tile_of.push_back(*tile);
  }
  for (std::size_t i = 0; i < manifest.tiles.size(); ++i)
    if (!map_of.count(i))
      throw ConfigError(tiles_json + ": tile '" + manifest.tiles[i].name +
                        "' has no map among the " + std::to_string(maps.size()) +
                        " given (stitch needs every tile's map once)");
  return tile_of;
}

}  // namespace mapfuse::io
