#pragma once
/// @file Trajectory metrics of aligned (or georeferenced) LSMs against the simulator's true
/// trajectories (docs/simulate.md "True trajectory"): absolute trajectory error (ATE) and
/// relative pose error (RPE) over a fixed travelled distance, keyframes matched to the truth by
/// time stamp (interpolated between true poses). The truth is re-expressed in the LSM's ENU
/// frame, so no alignment is estimated (docs/evaluate.md).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mapfuse/core/lsm.hpp"
#include "mapfuse/core/param.hpp"
#include "mapfuse/eval/error_stats.hpp"

namespace mapfuse::eval {

struct TruePose {
  int64_t id = 0;  ///< simulator keyframe or camera frame index (informative)
  double stamp = 0.0;
  Pose3 T_enu_body = Pose3::Identity();
};

/// A `mapfuse.trajectory` file written by simulate.
struct TrueTrajectory {
  std::string drive_id;
  geo::GeoOrigin origin;
  std::vector<TruePose> poses;
};

/// @brief The poses of `truth` ordered by stamp (pointers into it), for truePoseAt.
std::vector<const TruePose*> sortedByStamp(const TrueTrajectory& truth);

/// @brief The true pose at `stamp` from poses sorted by stamp: the pose with that stamp, else
/// interpolated between its two neighbours; nullopt outside their span. Keyframes are matched
/// to the truth by stamp because ids differ when lsm-build chose its own keyframes.
std::optional<Pose3> truePoseAt(const std::vector<const TruePose*>& sorted, double stamp);

/// @brief Reads a `mapfuse.trajectory` file (JSON or CBOR). @throws IoError, ParseError.
TrueTrajectory readTrueTrajectory(const std::filesystem::path& path);

/// @brief Reads every `<drive>.trajectory.json` of `folder`, in file-name order, with the file
/// each came from. @throws IoError when `folder` is not a folder; IoError, ParseError.
std::vector<std::pair<std::filesystem::path, TrueTrajectory>> readTrueTrajectories(
    const std::filesystem::path& folder);

/// Parameters of the trajectory comparison (compareTrajectory takes rpe_distance).
struct TrajectoryEvalSettings {
  double rpe_distance = 10.0;  ///< m, travelled distance of the relative pose error

  template <class V>
  void visit(V& v) {
    v("rpe_distance", rpe_distance, "m", "travelled distance of the relative pose error",
      param::gt(0));
  }
};

struct TrajectoryMetrics {
  std::string drive_id;
  std::size_t matched = 0;     ///< keyframes found in both
  ErrorStats ate_translation;  ///< m, |t_est - t_true|
  ErrorStats ate_rotation;     ///< deg, angle of R_true^T R_est
  ErrorStats rpe_translation;  ///< m, over segments of `rpe_distance` travelled metres
  ErrorStats rpe_rotation;     ///< deg
};

/// @brief Compares the keyframes of `lsm` (frame enu, same origin as the truth) with the truth.
/// @throws InputError when the LSM is not in enu, the origins differ or no keyframe id matches.
TrajectoryMetrics compareTrajectory(const Lsm& lsm, const TrueTrajectory& truth,
                                    double rpe_distance, const std::string& source);

nlohmann::json toJson(const TrajectoryMetrics& m);

}  // namespace mapfuse::eval
