#pragma once
/// @file The parameters of aggregation (§4.3, Song et al. 2023; docs/aggregate.md), each declared
/// once in a `visit` with its config key, unit, help and rule (mapfuse/core/param.hpp). The
/// `aggregate` stage composes them (stages/aggregate.hpp); aggregateObservations takes them.
/// Bounds that a real map never reaches keep a typo from exhausting memory or time (a tile or a
/// station of a micrometre, a DBSCAN radius of a kilometre).
#include <string>

#include "mapfuse/core/param.hpp"

namespace mapfuse::aggregate {

/// Lane-line instantiation by two-stage DBSCAN (lane_instantiation.cpp).
struct LaneInstantiationParams {
  double buffer_width = 0.2;         ///< m, half width of the buffer polygon (stage 1)
  double min_overlap_ratio = 0.3;    ///< stage-1 eps: overlap area / smaller polygon area
  double piece_angle_deg = 20.0;     ///< deg, stage 1: pieces crossing at more are not neighbours
  int min_pts = 3;                   ///< stage-1 MinPts (capped by the number of drives)
  double tile_size = 10.0;           ///< m, edge of the square tiles observations are cut at
  double resample_step = 0.25;       ///< m, spacing of the points averaged into centrelines
  double station_step = 1.0;         ///< m, bin length of fragment centrelines
  double link_distance = 8.0;        ///< m, stage-2 eps: longitudinal gap between linked ends
  double link_lateral = 1.0;         ///< m, largest lateral offset of a linked end
  double link_angle_deg = 30.0;      ///< deg, largest direction change across a link
  int link_min_pts = 1;              ///< stage-2 MinPts
  int link_max_pts = 2;              ///< stage-2 MaxPts (|N_eps| counts the end itself)
  double min_instance_length = 3.0;  ///< m, shorter instances are dropped
  /// an observation is compared with those of at most this many other drives (stage 1, and
  /// the discrete classes' DBSCAN too): bounded work whatever the number of traversals
  int partner_drives = 4;

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("buffer_width", buffer_width, "m", "stage 1: half width of the lane buffer polygons",
      gt(0) & le(10));
    v("min_overlap_ratio", min_overlap_ratio, "",
      "stage 1 eps: overlap area / smaller polygon area for neighbours", gt(0) & le(1));
    v("piece_angle_deg", piece_angle_deg, "deg",
      "stage 1: overlapping pieces whose directions differ more than this where they meet are "
      "not neighbours (crossing lines); 90: off",
      gt(0) & le(90));
    v("lane_min_pts", min_pts, "", "stage 1 MinPts (capped by the number of drives)",
      in(1, 1000000));
    // pieces of observations number (observed length / tile_size)
    v("tile_size", tile_size, "m", "stage 1: observations are cut at a square tiling of this size",
      in(2, 1000));
    v("resample_step", resample_step, "m",
      "spacing of the fragment points averaged into centrelines", in(0.01, 10));
    // an arc link is bridged by points every station_step
    v("station_step", station_step, "m", "bin length of fragment centrelines", in(0.01, 100));
    v.relation("tile_size", tile_size, tile_size >= 2 * station_step, ">= 2 * station_step");
    // the stage-2 candidates of an end are the ends within max(link_distance, link_lateral)
    v("link_distance", link_distance, "m", "stage 2 eps: longest gap between linked fragments",
      gt(0) & le(100));
    v("link_lateral", link_lateral, "m", "stage 2: largest lateral offset across a link",
      gt(0) & le(10));
    v("link_angle_deg", link_angle_deg, "deg", "stage 2: largest direction change across a link",
      gt(0) & lt(90));
    v("link_min_pts", link_min_pts, "", "stage 2 MinPts", in(1, 1000));
    v("link_max_pts", link_max_pts, "", "stage 2 MaxPts (2: one follower; forks start instances)",
      in(1, 1000));
    v.relation("link_max_pts", link_max_pts, link_max_pts >= link_min_pts, ">= link_min_pts");
    v("min_instance_length", min_instance_length, "m", "shorter lane instances are dropped", ge(0));
    v("partner_drives", partner_drives, "",
      "DBSCAN compares an observation with those of at most this many other drives (0 = all)",
      in(0, 1000000));
  }
};

/// Vectorization of a lane instance (bezier_fit.cpp, eq. (15)).
struct BezierFitParams {
  double max_deviation = 0.08;  ///< m, largest allowed point-to-curve distance
  int reparam_iterations = 4;   ///< Newton re-parametrisation rounds per fit
  double tangent_window = 3.0;  ///< m, arc length used to estimate end tangents

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("max_deviation", max_deviation, "m", "largest Bezier deviation from the centreline", gt(0));
    v("bezier_reparam_iterations", reparam_iterations, "",
      "Newton re-parametrisation rounds per Bezier fit", in(0, 100));
    v("bezier_tangent_window", tangent_window, "m",
      "arc length used to estimate a Bezier chain's end tangents", gt(0) & le(100));
  }
};

/// Clustering and merging of the discrete elements (discrete_merge.cpp).
struct DiscreteMergeParams {
  double min_iou = 0.2;             ///< arrows, crosswalks: eps = 1 - min_iou on 1 - IoU
  double sign_radius = 1.0;         ///< m, traffic signs: eps on 3D centroid distance
  double point_radius = 1.0;        ///< m, poles and lights: eps on 3D base distance
  double stop_line_radius = 1.5;    ///< m, stop lines: eps on midpoint-to-segment distance
  double stop_line_angle_deg = 20;  ///< deg, stop lines: largest direction difference
  int min_pts = 3;                  ///< DBSCAN MinPts (capped by the number of drives)

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("min_iou", min_iou, "", "arrows/crosswalks: DBSCAN eps as 1 - IoU <= 1 - min_iou",
      gt(0) & le(1));
    // every element within the radius is a neighbour: the lists grow with its square
    v("sign_radius", sign_radius, "m", "traffic signs: DBSCAN eps on 3D distance", gt(0) & le(20));
    v("point_radius", point_radius, "m", "poles/lights: DBSCAN eps on 3D distance", gt(0) & le(20));
    v("stop_line_radius", stop_line_radius, "m",
      "stop lines: DBSCAN eps on the distance of a midpoint to the other line", gt(0) & le(20));
    v("stop_line_angle_deg", stop_line_angle_deg, "deg",
      "stop lines: largest direction difference within one cluster", gt(0) & le(90));
    v("discrete_min_pts", min_pts, "", "discrete MinPts (capped by the number of drives)",
      in(1, 1000000));
  }
};

/// The grid-vote baseline of Qin et al. 2021 (grid_vote.cpp): the ground classes rasterised into
/// square cells holding per-class vote counts, the best class per cell.
struct GridVoteParams {
  double cell_size = 0.1;    ///< m, cell edge (Qin et al. 2021: 0.1 m)
  int min_votes = 3;         ///< fewest votes for a cell to take a class (capped by the drives)
  double line_width = 0.15;  ///< m, width lane and stop lines are painted into the grid with

  template <class V>
  void visit(V& v) {
    using namespace param;
    // cells are hashed, so memory grows with the painted area / cell_size^2
    v("grid_cell_size", cell_size, "m", "grid_vote: cell edge", in(0.02, 2));
    v("grid_min_votes", min_votes, "",
      "grid_vote: fewest votes for a cell to take a class (capped by the number of drives)",
      in(1, 1000000));
    v("grid_line_width", line_width, "m", "grid_vote: width lines are painted into the grid with",
      in(0, 2));
  }
};

/// Everything aggregateObservations takes.
struct AggregatorParams {
  /// "dbscan_bezier": §4.3 of Song et al. 2023; "grid_vote": the Qin et al. 2021 baseline
  std::string method = "dbscan_bezier";
  LaneInstantiationParams lanes;
  BezierFitParams bezier;
  DiscreteMergeParams discrete;
  GridVoteParams grid;
  double sample_step = 0.5;  ///< m, spacing of the sampled "points" of lane lines

  template <class V>
  void visit(V& v) {
    v("method", method, "",
      "dbscan_bezier (Song et al. 2023) | grid_vote (Qin et al. 2021 baseline, ground classes)",
      param::oneOf({"dbscan_bezier", "grid_vote"}));
    lanes.visit(v);
    bezier.visit(v);
    v("sample_step", sample_step, "m", "spacing of the sampled lane-line points",
      param::in(0.01, 100));
    discrete.visit(v);
    grid.visit(v);
  }
};

}  // namespace mapfuse::aggregate
