#pragma once
/// @file Placement of independently aligned tiles (stage `balance`): carries each drive's
/// georef error across the tiles it runs through, as one untiled align would.
///
/// Inside a tile, `align` registers drive pieces to each other; each connected *group* of pieces
/// (linked by the registrations its pose graph kept, or agreeing after GBA) ends up at the mean
/// georef error of its own pieces, o_g, because nothing else pins it. Untiled, the same drives
/// are also tied to the drives they meet elsewhere, through their odometry, so a group that
/// only sees a few drives in one tile is still placed by the whole batch. A drive keyframe keeps
/// its georef error e_k whichever tile it is seen in (neighbouring tiles share the keyframes of
/// their overlap margins), and e_k drifts slowly along the drive (a GPS bias: random walk in
/// time). So the shift align applied to keyframe k in tile t,
///
///   s_tk = aligned - georef position = o_g(t, k) - e_k,
///
/// observed for every keyframe of every tile, determines all o_g and e_k together up to one
/// common shift per set of drives that meet (share a group somewhere), fixed by taking the
/// georef errors of that set as zero-mean (the untiled run's assumption: drives that never meet
/// are placed by their own GPS alone). Moving every group by -o_g then puts all groups of all
/// tiles where one untiled graph would. Linear least squares (per axis, one sparse normal
/// matrix), iteratively reweighted per piece (Cauchy) so that a piece whose alignment went wrong
/// does not move its group.
#include <Eigen/Core>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "mapfuse/core/lsm.hpp"
#include "mapfuse/core/param.hpp"
#include "mapfuse/tiling/tile_grid.hpp"

namespace mapfuse::tiling {

struct PlacementParams {
  double keyframe_sigma = 0.1;  ///< m: 1-sigma of align's shift of one keyframe
  double bias_walk = 0.05;      ///< m/sqrt(s): random walk of a drive's georef error in time
  double robust_scale = 0.3;    ///< m: Cauchy scale; a piece this far off the model counts half
  int rounds = 4;               ///< reweighting rounds (1 = plain least squares)

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("keyframe_sigma", keyframe_sigma, "m", "1-sigma of align's shift of one keyframe",
      gt(0) & le(1000));
    v("bias_walk", bias_walk, "m/sqrt(s)", "random walk of a drive's georef error in time",
      in(0, 1000));
    v("robust_scale", robust_scale, "m",
      "Cauchy scale of piece residuals (pieces further off count less)", gt(0) & le(1000));
    v("rounds", rounds, "", "reweighting rounds (1 = plain least squares)", in(1, 100));
  }
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

/// What align did to one keyframe of a piece: aligned - georef position (ENU, m).
struct KeyframeShift {
  int64_t id = 0;
  double stamp = 0.0;  ///< s
  Eigen::Vector3d shift = Eigen::Vector3d::Zero();
};

/// What align did to one drive piece.
struct TilePiece {
  GroupKey group;
  std::string drive;  ///< drive identity (see driveOfPiece)
  std::vector<KeyframeShift> keyframes;
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
  int keyframes = 0;          ///< distinct drive keyframes (unknowns e_k)
  int downweighted = 0;       ///< pieces further than robust_scale off the model, last round
  double rms_residual = 0.0;  ///< m, horizontal, over every keyframe of every piece, last round
  double max_shift = 0.0;     ///< m, largest horizontal group shift
};

/// @brief Shift to add to every coordinate of each group's pieces (ENU, m): -o_g of the model
/// above. @throws ConfigError on invalid params.
std::map<GroupKey, Eigen::Vector3d> solvePlacement(const std::vector<TilePiece>& pieces,
                                                   const PlacementParams& params,
                                                   PlacementReport& report);

}  // namespace mapfuse::tiling
