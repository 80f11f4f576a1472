#include "mapfuse/io/tiles_manifest.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "mapfuse/io/bounds.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/json_geometry.hpp"
#include "relative_path.hpp"

namespace mapfuse::io {

namespace {
/// A tile's `core` must be the grid's [ix*size, iy*size, (ix+1)*size, (iy+1)*size] (formats.md
/// "Tiled runs"): `tile` writes it, so any other value means the manifest was edited or mixed.
void checkCore(const JsonView& core, const TilesManifestTile& tile, double size) {
  if (core.size() != 4) core.fail("must be [min_x, min_y, max_x, max_y]");
  const double want[4] = {double(tile.ix) * size, double(tile.iy) * size,
                          double(tile.ix + 1) * size, double(tile.iy + 1) * size};
  for (std::size_t k = 0; k < 4; ++k) {
    const double got = core.at(k).number();
    if (std::abs(got - want[k]) > kCoreTolerance * std::max(1.0, std::abs(want[k])))
      core.at(k).fail(std::to_string(got) + " is not the grid's " + std::to_string(want[k]) +
                      " for tile (" + std::to_string(tile.ix) + ", " + std::to_string(tile.iy) +
                      ")");
  }
}
}  // namespace

TilesManifest tilesManifestFromJson(const Json& doc, const std::string& file) {
  const JsonView v(doc, file);
  v.onlyKeys({"format", "version", "tile_size", "margin", "origin", "tiles"});
  v.checkFormat("mapfuse.tiles", 1);
  TilesManifest m;
  m.tile_size = v.at("tile_size").number(1.0, bounds::kMaxCoordinate);
  m.margin = v.at("margin").number(0.0, bounds::kMaxCoordinate);
  if (!(m.margin < m.tile_size / 2)) v.at("margin").fail("must be below tile_size / 2");
  if (auto o = v.find("origin")) m.origin = readOrigin(*o);
  const auto max_index = int64_t(std::floor(bounds::kMaxCoordinate / m.tile_size));
  std::set<std::string> names, files;
  std::set<std::pair<int64_t, int64_t>> keys;
  const JsonView tiles = v.at("tiles");
  for (std::size_t i = 0; i < tiles.size(); ++i) {
    const JsonView t = tiles.at(i);
    t.onlyKeys({"name", "ix", "iy", "core", "lsms"});
    TilesManifestTile tile;
    tile.name = t.at("name").string();
    if (!relativeNameProblem(tile.name).empty() || tile.name.find('/') != std::string::npos)
      t.at("name").fail("'" + tile.name.substr(0, 80) + "' is not a folder name");
    if (!names.insert(tile.name).second) t.at("name").fail("'" + tile.name + "' given twice");
    tile.ix = t.at("ix").integer(-max_index, max_index);
    tile.iy = t.at("iy").integer(-max_index, max_index);
    if (!keys.insert({tile.ix, tile.iy}).second)
      t.at("iy").fail("tile (" + std::to_string(tile.ix) + ", " + std::to_string(tile.iy) +
                      ") given twice");
    if (auto core = t.find("core")) checkCore(*core, tile, m.tile_size);
    const JsonView lsms = t.at("lsms");
    for (std::size_t k = 0; k < lsms.size(); ++k) {
      const std::string f = lsms.at(k).string();
      if (const std::string why = relativeNameProblem(f); !why.empty()) lsms.at(k).fail(why);
      if (!files.insert(f).second) lsms.at(k).fail("'" + f + "' is listed twice");
      tile.lsms.push_back(f);
    }
    m.tiles.push_back(std::move(tile));
  }
  return m;
}

TilesManifest readTilesManifest(const std::filesystem::path& path) {
  return tilesManifestFromJson(readDocument(path), path.string());
}

}  // namespace mapfuse::io
