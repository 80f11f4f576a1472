#pragma once
/// @file Localisation errors against the simulator's true trajectory, as Song et al. 2023 report
/// them (Fig. 12): per keyframe the position error split along the true heading (longitudinal,
/// x forward) and across it (lateral, y left), and the heading error; their mean absolute values
/// over the localised keyframes. The prior's (GPS / georef) errors are given beside them.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "mapfuse/eval/trajectory_metrics.hpp"
#include "mapfuse/localize/localizer.hpp"

namespace mapfuse::localize {

struct PlanarError {
  Eigen::Vector2d enu = Eigen::Vector2d::Zero();  ///< m, estimated minus true position, ENU
  double true_yaw = 0.0;                          ///< rad, heading of the true pose
  double lateral = 0.0;                           ///< m, along the true body y (left positive)
  double longitudinal = 0.0;                      ///< m, along the true body x (forward positive)
  double heading_deg = 0.0;  ///< deg, estimated minus true yaw, wrapped to (-180, 180]
};

struct KeyframeError {
  int64_t id = 0;
  double distance = 0.0;  ///< m travelled (prior poses)
  bool lost = false;
  PlanarError localized;  ///< of the localised pose
  PlanarError prior;      ///< of the georeferenced prior
  PlanarError in_map;     ///< of the localised pose against the truth carried into the map frame
};

/// Mean absolute errors (the paper's three averages).
struct MeanAbsError {
  int count = 0;
  double lateral = 0.0;       ///< m
  double longitudinal = 0.0;  ///< m
  double heading_deg = 0.0;   ///< deg
};

struct LocalizeErrors {
  std::vector<KeyframeError> keyframes;  ///< keyframes the truth covers (by stamp)
  MeanAbsError localized;                ///< over the keyframes not lost
  MeanAbsError prior;                    ///< over the same keyframes
  MeanAbsError in_map;  ///< localised, against the truth in the map's frame (map_frame.hpp)
};

/// @brief Planar error of `T_est` against `T_true` (both ENU of one origin).
PlanarError planarError(const Pose3& T_est, const Pose3& T_true);

/// @brief Errors of a localisation against the true trajectory, keyframes matched by stamp
/// (eval::truePoseAt); the truth is re-expressed in `origin` (the drive's) when its own differs.
/// `in_map`: against the true pose carried into the map's frame, T_truth_map^-1 T_true
/// (T_truth_map from estimateMapToTruth in the same ENU frame; identity: the same as localized).
/// @throws InputError naming `source` when no keyframe falls in the truth's time span.
LocalizeErrors localizeErrors(const LocalizeResult& result, const eval::TrueTrajectory& truth,
                              const geo::GeoOrigin& origin, const std::string& source,
                              const Pose3& T_truth_map = Pose3::Identity());

/// Which error of a keyframe to pool.
enum class ErrorOf { kLocalized, kPrior, kInMap };

/// @brief Mean absolute errors of several drives' errors pooled keyframe by keyframe, over the
/// keyframes not lost.
MeanAbsError pooled(const std::vector<LocalizeErrors>& drives, ErrorOf which);

/// @brief Mean signed ENU position error of the localised keyframes of all drives (m): the
/// common offset of the map against the truth when the drives share one map.
Eigen::Vector2d commonOffset(const std::vector<LocalizeErrors>& drives);

/// @brief Mean absolute lateral / longitudinal errors of the localised keyframes once `offset`
/// (ENU, m) is taken off every position error: the localisation relative to the map's own frame
/// (heading unchanged).
MeanAbsError pooledWithoutOffset(const std::vector<LocalizeErrors>& drives,
                                 const Eigen::Vector2d& offset);

}  // namespace mapfuse::localize
