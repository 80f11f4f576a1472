#pragma once
/// @file Internals of align stage 1 shared by align_submaps.cpp, align_coarse.cpp and
/// align_register.cpp (private to libmapfuse/src/fusion).
#include <Eigen/Core>
#include <vector>

#include "mapfuse/fusion/align.hpp"

namespace mapfuse::fusion::detail {

/// Registration labels: the crowd classes, plus dashed lane lines as their own label so that a
/// dashed divider never matches a solid centre or edge line one lane width away.
constexpr int kLabelDashedLine = kNumCrowdClasses;
constexpr int kNumAlignLabels = kNumCrowdClasses + 1;

/// @brief Registration label of an element (class, or kLabelDashedLine).
int alignLabel(const Element& e);

/// @brief Per-label weights from per-class weights (dashed lines weigh like lane lines).
std::vector<double> labelWeights(const std::vector<double>& class_weights);

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

struct CoarseResult {
  Eigen::Vector2d t = Eigen::Vector2d::Zero();  ///< m, shift that maps B onto A
  double score = 0;                             ///< votes at the peak
};

/// Displacement histogram a - b over [-half, half]^2 bins of `bin` m (row-major, y rows).
struct VoteGrid {
  int half = 0;
  double bin = 0.5;
  std::vector<double> votes;
  void add(const VoteGrid& o, double w) {
    for (std::size_t i = 0; i < votes.size() && i < o.votes.size(); ++i) votes[i] += w * o.votes[i];
  }
};

/// @brief Votes of every same-label pair (a, b) within `radius` (weights per label, bilinear).
VoteGrid voteDisplacements(const Cloud& A, const Cloud& B, const std::vector<double>& weights,
                           double radius, double bin);

/// @brief Peak of a (summed) vote grid after [1 2 1]^2 smoothing and the Gaussian prior.
CoarseResult votePeak(const VoteGrid& g, double prior_sigma);

}  // namespace mapfuse::fusion::detail
