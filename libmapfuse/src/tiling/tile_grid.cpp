#include "mapfuse/tiling/tile_grid.hpp"

#include <cmath>

#include "mapfuse/core/error.hpp"

namespace mapfuse::tiling {

std::string TileKey::name() const {
  auto part = [](int64_t v) { return v < 0 ? "m" + std::to_string(-v) : std::to_string(v); };
  return "tile_" + part(ix) + "_" + part(iy);
}

TileGrid::TileGrid(double size, double margin) : size_(size), margin_(margin) {
  if (!(size > 0.0))
    throw ConfigError("TileGrid::size = " + std::to_string(size) +
                      ". Violated constraint: size > 0");
  if (!(margin >= 0.0) || margin >= size / 2)
    throw ConfigError("TileGrid::margin = " + std::to_string(margin) +
                      ". Violated constraint: 0 <= margin < size / 2");
}

TileKey TileGrid::keyOf(double x, double y) const {
  return {static_cast<int64_t>(std::floor(x / size_)), static_cast<int64_t>(std::floor(y / size_))};
}

Rect TileGrid::core(const TileKey& k) const {
  return {k.ix * size_, k.iy * size_, (k.ix + 1) * size_, (k.iy + 1) * size_};
}

Rect TileGrid::withMargin(const TileKey& k) const {
  const Rect c = core(k);
  return {c.min_x - margin_, c.min_y - margin_, c.max_x + margin_, c.max_y + margin_};
}

std::vector<TileKey> TileGrid::tilesTouching(double x, double y) const {
  std::vector<TileKey> out;
  const TileKey center = keyOf(x, y);
  for (int64_t dx = -1; dx <= 1; ++dx)
    for (int64_t dy = -1; dy <= 1; ++dy) {
      const TileKey k{center.ix + dx, center.iy + dy};
      if (withMargin(k).contains(x, y)) out.push_back(k);
    }
  return out;
}

}  // namespace mapfuse::tiling
