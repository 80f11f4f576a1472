#pragma once
/// @file Lane-line instantiation by two-stage DBSCAN (§4.3.1, Song et al. 2023).
///
/// Stage 1: every lane observation is cut at the edges of a square tiling (so clusters stay
/// local and forks can be seen), each piece is buffered by ±buffer_width into a polygon
/// (boost::geometry::buffer) and pieces of one tile are clustered by DBSCAN with the overlap
/// area (intersection / smaller polygon, exact: aggregate/polygon_overlap.hpp) as similarity;
/// candidates are the pieces of the same tile with touching boxes; noise pieces are dropped. Each
/// cluster (a MultiLineString) is reduced to a centreline fragment by averaging its points in
/// station bins along its principal direction.
///
/// Stage 2: fragments are clustered with a line-to-line (end-to-end) Euclidean distance and the
/// modified core-object rule MinPts <= |N_eps| <= MaxPts (MinPts = 1, MaxPts = 2): a fragment
/// end is linked to the fragment that follows it only when each of the two ends has exactly one
/// such neighbour, so a line connects to at most the line that follows it and a fork or merge
/// (an end with two followers) starts new instances. Stage-2 candidate pairs come from a
/// Boost.Geometry rtree, so the cost grows ~ n log n.
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "mapfuse/aggregate/observations.hpp"

namespace mapfuse::aggregate {

struct LaneInstantiationParams {
  double buffer_width = 0.2;         ///< m, half width of the buffer polygon (stage 1)
  double min_overlap_ratio = 0.3;    ///< stage-1 eps: overlap area / smaller polygon area
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
  int partner_drives = 4;  ///< stage 1: a piece is compared with those of <= this many drives
};

/// One lane-line instance before vectorization.
struct LaneInstance {
  std::vector<Eigen::Vector3d> centreline;  ///< ENU, ordered along the line
  std::vector<std::size_t> observations;    ///< indices into the observation list (sorted)
  int fragments = 0;                        ///< stage-1 fragments chained into it
};

struct LaneInstantiationStats {
  std::size_t pieces = 0;         ///< observation pieces after tiling
  std::size_t comparisons = 0;    ///< stage-1 overlap tests (pairs of pieces with touching boxes)
  std::size_t noise_pieces = 0;   ///< dropped by stage 1
  std::size_t fragments = 0;      ///< stage-1 clusters (after merging split ones)
  std::size_t links = 0;          ///< stage-2 links
  std::size_t branch_ends = 0;    ///< fragment ends with more than one follower (forks/merges)
  std::size_t dropped_short = 0;  ///< instances below min_instance_length
};

struct LaneInstantiation {
  std::vector<LaneInstance> instances;
  LaneInstantiationStats stats;
};

/// @brief Two-stage DBSCAN over the lane-line observations `indices` of `items`.
/// @param num_drives number of input drives (MinPts is capped by it).
LaneInstantiation instantiateLanes(const std::vector<Observation>& items,
                                   const std::vector<std::size_t>& indices,
                                   const LaneInstantiationParams& params, int num_drives);

}  // namespace mapfuse::aggregate
