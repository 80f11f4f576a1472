#pragma once
/// @file The GPS prior of align's pose graph and GBA (eq. (9), Song et al. 2023) with a slowly
/// varying bias per traversal (issue 36; private to libmapfuse/src/fusion).
///
/// A receiver's error is mostly a bias that wanders slowly (multipath, atmosphere, the
/// correction service) plus white noise: the simulator draws 1-3 m of initial bias and a random
/// walk of 0.05 m/sqrt(s), against 0.5 m of white noise. Eq. (9) read literally puts one
/// independent prior on every keyframe, so a traversal's keyframes, a thousand of them, pin it
/// to its own GPS as if their errors averaged out; where two routes share a road, the
/// registrations tie them there, but a hundred metres further each sits at its own bias again,
/// and a map of many routes shows each route's bias (issue 36: lane completeness 0.88 with 8
/// routes against 0.996 with one).
///
/// Here the prior of keyframe k is relative to a bias node of its traversal:
///   r_k = L_k [ (t_k - b_j) - g_k ; rotation ],
/// b_j the node nearest in time, nodes every `gps_bias_interval` s (piecewise constant: two
/// nodes differ by gps_bias_walk sqrt(interval), 0.16 m at the defaults; interpolating between
/// two nodes, tried first, gave the same maps for 18 % more align memory), the nodes a random
/// walk of `gps_bias_walk` m/sqrt(s) with a zero-mean prior of `gps_bias_sigma` (horizontal) /
/// `gps_bias_vertical_sigma` on the first, each at most the drive's median keyframe sigma (an
/// accurate receiver's drive is held as tightly as before). A bias node is a pose whose
/// translation is its anchor (the traversal's georeferenced position at the node) plus the
/// bias and whose rotation is held at the identity, so that the
/// terms are the relative-pose terms of eq. (10) / (11) and any pose-graph solver (ours, Ceres)
/// takes them as they are. Registrations then move a traversal's bias, not one keyframe, and a
/// road driven by few traversals shares the mean bias of every traversal tied to them.
/// `gps_bias_sigma` = 0 restores the independent priors of eq. (9).
#include <vector>

#include "mapfuse/core/lsm.hpp"
#include "mapfuse/core/se3.hpp"
#include "mapfuse/fusion/align.hpp"

namespace mapfuse::fusion::detail {

/// One term between two poses: T_a^-1 T_b = T_ab with square-root information L (6 x 6); a pose
/// is (chain, index), as PoseProblem::poseIndex takes it.
struct GpsPriorTerm {
  int chain_a = 0, index_a = 0;  ///< chain: a traversal (< lsms) or its bias chain (lsms + l)
  int chain_b = 0, index_b = 0;
  Pose3 T_ab = Pose3::Identity();
  Matrix6d L = Matrix6d::Zero();
};

/// A prior on one pose: T ~ T0 with square-root information L.
struct GpsPriorAnchor {
  int chain = 0, index = 0;
  Pose3 T0 = Pose3::Identity();
  Matrix6d L = Matrix6d::Zero();
};

struct GpsPriorTerms {
  /// Per traversal, its bias nodes' anchor poses (identity rotation), in stamp order; empty
  /// lists when the model is off. Chains lsms.size() + l in the problem.
  std::vector<std::vector<Pose3>> nodes;
  /// Per traversal and node, the keyframe whose georeferenced position anchors it.
  std::vector<std::vector<int>> node_keyframe;
  std::vector<GpsPriorAnchor> anchors;  ///< keyframe priors (model off) or node priors
  std::vector<GpsPriorTerm> terms;      ///< keyframe-to-node ties and the nodes' random walk
};

/// @brief The GPS prior terms of the georeferenced keyframes `priors` (eq. (9), with the bias
/// model above when s.gps_bias_sigma > 0). O(keyframes).
GpsPriorTerms gpsPriorTerms(const std::vector<Lsm>& priors, const AlignSettings& s);

/// @brief Initial bias-node poses consistent with the current keyframes `lsms`: each node's
/// anchor moved by its keyframe's offset from its prior. Chain after chain, as `nodes`.
std::vector<Pose3> gpsBiasNodeStart(const GpsPriorTerms& g, const std::vector<Lsm>& lsms,
                                    const std::vector<Lsm>& priors);

}  // namespace mapfuse::fusion::detail
