#pragma once
/// @file A fixed ENU tile grid for scaling crowd fusion beyond one machine (DESIGN.md "Scale
/// beyond one machine"): tiles of `size` metres whose cores partition the plane (half-open
/// intervals, so every point belongs to exactly one core) and whose margins overlap.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace mapfuse::tiling {

/// Integer index of a tile: core = [ix*size, (ix+1)*size) x [iy*size, (iy+1)*size).
struct TileKey {
  int64_t ix = 0;
  int64_t iy = 0;
  bool operator<(const TileKey& o) const { return ix != o.ix ? ix < o.ix : iy < o.iy; }
  bool operator==(const TileKey& o) const { return ix == o.ix && iy == o.iy; }
  /// @brief "tile_<ix>_<iy>" (negative indices as "m3"), used for folder names.
  std::string name() const;
};

/// Axis-aligned rectangle in the EN plane (m).
struct Rect {
  double min_x, min_y, max_x, max_y;
  /// @brief Half-open containment [min, max) used for core ownership.
  bool ownsPoint(double x, double y) const {
    return x >= min_x && x < max_x && y >= min_y && y < max_y;
  }
  /// @brief Closed containment used for margins.
  bool contains(double x, double y) const {
    return x >= min_x && x <= max_x && y >= min_y && y <= max_y;
  }
};

class TileGrid {
 public:
  /// @param size tile edge (m, > 0); @param margin overlap added on every side (m, >= 0).
  TileGrid(double size, double margin);
  double size() const { return size_; }
  double margin() const { return margin_; }
  TileKey keyOf(double x, double y) const;
  Rect core(const TileKey& k) const;
  Rect withMargin(const TileKey& k) const;
  /// @brief Every tile whose margin rectangle contains (x, y) (1 to 4 tiles when margin < size/2).
  std::vector<TileKey> tilesTouching(double x, double y) const;

 private:
  double size_, margin_;
};

}  // namespace mapfuse::tiling
