#pragma once
/// @file Internals of align stage 1 shared by align_submaps.cpp, align_coarse.cpp and
/// align_register.cpp (private to libmapfuse/src/fusion).
#include <Eigen/Core>
#include <vector>

#include "mapfuse/fusion/align.hpp"
#include "mapfuse/fusion/displacement_vote.hpp"

namespace mapfuse::fusion::detail {

/// @brief Registration label of an element (class, or kLabelDashedLine).
int alignLabel(const Element& e);

/// A chunk of one LSM's keyframes and its element points in the LSM (ENU) frame. The full cloud
/// (every point with its covariance, ~100 B a point) is built only while the submap is
/// registered (`submapCloud`): kept for every submap it took 0.5 GB at 1000 driven km.
struct Submap {
  int lsm = 0, kf_begin = 0, kf_end = 0, anchor = 0;
  std::vector<int> elements;  ///< indices of the LSM's elements anchored in [kf_begin, kf_end)
  Cloud coarse;  ///< voxel-downsampled (1 m) points and labels for the coarse level and overlap
  Eigen::Vector2d lo, hi;
};

/// @brief Submaps of `length` m of keyframe path; submaps with < 10 points are dropped.
/// O(keyframes + element points) per LSM, the LSMs on `threads` OpenMP threads (0: default).
std::vector<Submap> buildSubmaps(const std::vector<Lsm>& lsms, double length, int threads = 0);

/// @brief The registration cloud of a submap (elementCloud of its keyframe range); of solid lane
/// lines (free along the line) only every `solid_stride`-th point.
Cloud submapCloud(const std::vector<Lsm>& lsms, const Submap& m, int solid_stride = 1);

struct SubmapPair {
  int a = 0, b = 0;  ///< indices into the submaps, lsm(a) < lsm(b)
  double overlap = 0;
};

/// @brief Pairs of submaps of different LSMs to register, union over submaps, sorted. Every
/// submap picks `max_partners` other LSMs among those with a submap whose box lies within
/// `overlap_radius`, and in each its best-overlapping such submap (overlap = the smaller of the
/// two shares of coarse points with a same-label point within `overlap_radius` m), if it
/// overlaps at least `min_overlap`. `spread_partners`: the LSMs evenly spread over those present,
/// the offset rotating with the submap, a refused one replaced by its next (overlap computed
/// only for the chosen LSMs' submaps: O(partners) per submap, whatever the traversals there);
/// otherwise the best-overlapping LSMs (overlap computed for every candidate).
/// `overlaps` (optional) counts the overlap computations (two directed shares each).
std::vector<SubmapPair> selectPairs(const std::vector<Submap>& maps, const AlignSettings& s,
                                    long* overlaps = nullptr);


}  // namespace mapfuse::fusion::detail
