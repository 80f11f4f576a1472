#pragma once
/// @file Stitching per-tile vector maps into one map without duplicates or gaps at tile borders:
/// each tile keeps what its core owns (half-open, so exactly one tile owns any point), lines are
/// clipped to the core and the pieces that meet at a border are joined again.
#include <functional>
#include <utility>
#include <vector>

#include "mapfuse/core/param.hpp"
#include "mapfuse/core/vector_map.hpp"
#include "mapfuse/tiling/tile_grid.hpp"

namespace mapfuse::tiling {

struct StitchParams {
  static constexpr const char* kName = "StitchParams";
  double join_tolerance = 1.0;    ///< m: border ends of one line in two tiles closer than this join
  double min_piece_length = 0.5;  ///< m: shorter clipped line pieces are dropped

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("join_tolerance", join_tolerance, "m", "border ends of one line closer than this are joined",
      gt(0) & le(100));
    v("min_piece_length", min_piece_length, "m",
      "clipped line pieces shorter than this are dropped", in(0, 1000));
  }
};

struct StitchReport {
  int tiles = 0;
  int instances_in = 0;  ///< over all tile maps, margins included
  int instances_out = 0;
  int dropped_outside_core = 0;  ///< discrete instances owned by another tile
  int line_pieces = 0;           ///< line pieces after clipping to cores
  int joins = 0;                 ///< border joins made
};

/// Optional refit of a joined line's Bezier chain (e.g. aggregate's least-squares fitter).
using BezierRefit = std::function<std::vector<BezierSegment>(const std::vector<Eigen::Vector3d>&)>;

/// @brief Merges tile maps (all with one origin). Instance ids are re-assigned 1..n in a
/// deterministic order.
/// @throws InputError when origins differ.
VectorMap stitchTiles(const std::vector<std::pair<TileKey, VectorMap>>& tiles, const TileGrid& grid,
                      const StitchParams& params, StitchReport& report,
                      const BezierRefit& refit = nullptr);

/// @brief Parts of a polyline inside a rectangle (Liang–Barsky per segment). Each part records
/// whether its start/end were cut by the rectangle (open ends) or are the line's own ends.
struct ClippedPiece {
  std::vector<Eigen::Vector3d> points;
  bool start_cut = false;
  bool end_cut = false;
};
std::vector<ClippedPiece> clipPolyline(const std::vector<Eigen::Vector3d>& line, const Rect& r);

}  // namespace mapfuse::tiling
