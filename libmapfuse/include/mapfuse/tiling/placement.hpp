#pragma once
/// @file Placement of independently aligned tiles (stage `balance`): carries each drive's
/// georef error across the tiles it runs through, as one untiled align would.
///
/// Inside a tile, `align` registers drive pieces to each other; each connected *group* of pieces
/// (linked by the registrations its pose graph kept) ends up at the mean georef error of its own
/// pieces, o_g, because nothing else pins it. Untiled, the same drives are also tied to drives
/// they meet elsewhere, through their odometry, so a group that only sees a few drives in one
/// tile is still placed by the whole batch. A drive keeps its georef error e_p (GPS bias,
/// drifting slowly in time) from one tile to the next, so the shift align applied to piece p,
///
///   s_p = mean over p's keyframes of (aligned - georef) = o_g(p) - e_p,
///
/// observed for every piece of every tile, determines all o_g and e_p together up to one common
/// shift, fixed by taking the batch's georef errors as zero-mean (the untiled run's assumption).
/// Moving every group by -o_g then puts all groups of all tiles where one untiled graph would.
/// Linear least squares (per axis, one sparse normal matrix), iteratively reweighted (Cauchy) so
/// that a piece whose alignment went wrong does not move its group.
#include <Eigen/Core>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "mapfuse/core/lsm.hpp"
#include "mapfuse/tiling/tile_grid.hpp"

namespace mapfuse::tiling {

struct PlacementParams {
  double piece_sigma = 0.1;   ///< m: 1-sigma of one piece's mean align shift
  double bias_walk = 0.05;    ///< m/sqrt(s): random walk of a drive's georef error in time
  double robust_scale = 0.3;  ///< m: Cauchy scale; a piece this far off the model counts half
  int rounds = 4;             ///< reweighting rounds (1 = plain least squares)

  template <class V>
  void visit(V& v) {
    v("piece_sigma", piece_sigma, "m", "1-sigma of a drive piece's mean align shift");
    v("bias_walk", bias_walk, "m/sqrt(s)", "random walk of a drive's georef error in time");
    v("robust_scale", robust_scale, "m",
      "Cauchy scale of piece residuals (pieces further off count less)");
    v("rounds", rounds, "", "reweighting rounds (1 = plain least squares)");
  }
  void validate() const;
};

/// One registration group: the pieces of one tile that its align linked together.
struct GroupKey {
  TileKey tile;
  int group = 0;
  bool operator<(const GroupKey& o) const {
    return tile == o.tile ? group < o.group : tile < o.tile;
  }
  bool operator==(const GroupKey& o) const { return tile == o.tile && group == o.group; }
};

/// What align did to one drive piece.
struct TilePiece {
  GroupKey group;
  std::string drive;                                ///< drive identity (see driveOfPiece)
  double stamp = 0.0;                               ///< s: mean keyframe time of the piece
  Eigen::Vector3d shift = Eigen::Vector3d::Zero();  ///< m: mean aligned - georef position (ENU)
  int keyframes = 0;
};

/// @brief The drive a tile piece belongs to: its drive_id without a trailing ".run<k>" (tile
/// names the runs of a drive that enters a tile twice so).
std::string driveOfPiece(const std::string& drive_id);

/// @brief The piece `georef` (a tile's input LSM) as `aligned` (align's output for it) moved it,
/// keyframes matched by id; `group` is left for the caller.
/// @throws InputError when the drive ids differ or no keyframe id is shared.
TilePiece measurePiece(const Lsm& georef, const Lsm& aligned);

/// @brief Connected components of `n` items linked by `links` (index pairs), numbered 0.. in
/// order of their first item. @throws InputError on an index outside 0..n-1.
std::vector<int> registrationGroups(int n, const std::vector<std::pair<int, int>>& links);

struct PlacementReport {
  int tiles = 0;
  int groups = 0;
  int pieces = 0;
  int drives = 0;
  int downweighted = 0;       ///< pieces further than robust_scale off the model, last round
  double rms_residual = 0.0;  ///< m, horizontal, over pieces, last round
  double max_shift = 0.0;     ///< m, largest horizontal group shift
};

/// @brief Shift to add to every coordinate of each group's pieces (ENU, m): -o_g of the model
/// above. @throws ConfigError on invalid params.
std::map<GroupKey, Eigen::Vector3d> solvePlacement(const std::vector<TilePiece>& pieces,
                                                   const PlacementParams& params,
                                                   PlacementReport& report);

}  // namespace mapfuse::tiling
