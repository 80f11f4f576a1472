#pragma once
/// @file Consistency and accuracy of georeferenced / aligned LSMs against the simulator's truth
/// (docs/performance-fusion-accuracy.md): per true element, the spread of its observed position
/// across traversals and its absolute error, plus keyframe ATE against the true trajectories.
/// Evaluation code (it scores fusion output); used by tests/eval and
/// scripts/bench/bench_fusion_errors.cpp.
#include <map>
#include <string>
#include <vector>

#include "mapfuse/core/lsm.hpp"
#include "mapfuse/core/vector_map.hpp"
#include "mapfuse/eval/trajectory_metrics.hpp"

namespace mapfuse::eval {

struct ElementTruthErrors {
  int observations = 0;        ///< element observations with a known truth id
  int groups = 0;              ///< true elements (or 20 m pieces of long lines) seen by >= 2 drives
  double mean_abs = 0.0;       ///< m, mean horizontal error of an element observation vs truth
  double spread = 0.0;         ///< m, mean over groups of the RMS spread of per-drive mean offsets
  double spread_median = 0.0;  ///< m, median of the same
  double mean_offset = 0.0;    ///< m, norm of the mean offset over all observations (common shift)
};

/// @brief Element errors vs the true map. An observation's offset is the horizontal vector from
/// the truth to the observation: for lane and stop lines the mean offset of its points to their
/// nearest points on the true polyline (an observation often shows only part of a line, so
/// centroids would differ without any error), lane lines longer than `piece_length` grouped by
/// pieces of that arc length; for other elements centroid minus true centroid. Spread: per group,
/// the per-drive mean offsets' RMS distance to their mean. The truth is converted when its origin
/// differs.
/// @throws InputError when an LSM is not in enu.
ElementTruthErrors elementTruthErrors(const std::vector<Lsm>& lsms, const VectorMap& truth,
                                      double piece_length = 20.0);

struct TrajectoryTruthErrors {
  int drives = 0;
  double ate_mean = 0.0;   ///< m, mean over drives of the per-drive keyframe RMS position error
  double ate_max = 0.0;    ///< m, worst per-drive RMS
  double bias_mean = 0.0;  ///< m, mean over drives of |mean keyframe error| (common drive shift)
};

/// @brief Keyframe position errors vs true trajectories matched by drive id and keyframe id
/// (true positions converted into the LSM origin when it differs). @throws InputError when an
/// LSM is not in enu.
TrajectoryTruthErrors trajectoryTruthErrors(const std::vector<Lsm>& lsms,
                                            const std::map<std::string, TrueTrajectory>& truth);

}  // namespace mapfuse::eval
