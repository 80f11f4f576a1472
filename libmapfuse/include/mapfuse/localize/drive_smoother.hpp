#pragma once
/// @file Full-drive refinement of a localisation (docs/localize.md "Full-drive solve"): the poses
/// of all keyframes of a drive in one Ceres problem, each keyframe's own observations matched to
/// the map (eq. L1-L2), consecutive keyframes chained by the drive's relative motion (eq. L6) and
/// the GPS prior (eq. L3), so that the longitudinal evidence of a few elements (stop lines,
/// crosswalks, arrows, poles, signs) spreads over the keyframes before and after them. It starts
/// from the per-keyframe localisation (localizeDrive) and re-matches `smoother_rounds` times.
#include <string>

#include "mapfuse/core/param.hpp"
#include "mapfuse/localize/localizer.hpp"
#include "mapfuse/localize/map_index.hpp"

namespace mapfuse::localize {

struct SmootherSettings {
  std::string solve = "full_drive";        ///< per_keyframe | full_drive
  double odometry_sigma = 0.02;            ///< m, relative-motion noise per keyframe step
  double odometry_sigma_per_m = 0.015;     ///< m/m, its growth with the step's length
  double odometry_sigma_yaw_per_m = 2e-4;  ///< rad/m, heading noise of the relative motion
  int smoother_rounds = 3;                 ///< matching + solve rounds of the full-drive problem

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("solve", solve, "",
      "per_keyframe: each keyframe on its own (a filter over the drive); full_drive: then all "
      "keyframes of a drive in one problem chained by the drive's relative motion",
      oneOf({"per_keyframe", "full_drive"}));
    v("odometry_sigma", odometry_sigma, "m", "full_drive: relative-motion noise per keyframe step",
      gt(0) & le(100));
    v("odometry_sigma_per_m", odometry_sigma_per_m, "m/m",
      "full_drive: relative-motion noise per metre between two keyframes", in(0, 10));
    v("odometry_sigma_yaw_per_m", odometry_sigma_yaw_per_m, "rad/m",
      "full_drive: heading noise of the relative motion per metre", gt(0) & le(10));
    v("smoother_rounds", smoother_rounds, "", "full_drive: matching + solve rounds", in(1, 20));
  }
};

/// @brief Refines `result` (localizeDrive of the same drive) by the full-drive problem, eq.
/// (L1-L3, L6): every keyframe's pose changes, lost keyframes included (bridged by the relative
/// motion; they stay flagged lost); `matches` becomes the keyframe's own matched points and
/// `rms` their RMS distance. Adds the Ceres iterations and the time to `result`.
void smoothDrive(const MapIndex& map, const DriveObservations& drive,
                 const LocalizeSettings& settings, const SmootherSettings& smoother,
                 LocalizeResult& result);

}  // namespace mapfuse::localize
