#pragma once
/// @file How far an odometry track agrees with a reference track of the same motion (GPS fixes, or
/// the GPS-fused keyframes), per axis (issue 33: a stage states how far it can be trusted). The
/// odometry frame has z up and an arbitrary heading and origin: the horizontal residuals are
/// taken after the least-squares yaw + translation fit, the vertical ones after the mean offset.
/// A tilted dead reckoning climbs or sinks steadily (the vertical slope); a wheel scale error
/// stretches every distance (the scale error); GPS noise averages out over a drive.
#include <Eigen/Core>
#include <vector>

#include "mapfuse/core/se3.hpp"

namespace mapfuse::geo {

/// m of odometry per chord of the scale check: long enough for GPS noise (a few m) to shrink
/// to a few % of a chord, short enough for a 1 km drive to give several chords.
constexpr double kScaleWindow = 200.0;

struct TrackAgreement {
  int samples = 0;              ///< position pairs compared
  double length = 0.0;          ///< m, odometry path length over the pairs
  double horizontal_rms = 0.0;  ///< m, after the yaw + translation fit
  double vertical_rms = 0.0;    ///< m, after the mean offset
  double vertical_slope = 0.0;  ///< m/m, least-squares slope of (reference − odometry) height
                                ///< over odometry distance
  double scale_error = 0.0;     ///< median over chords of `scale_window` m of reference over
                                ///< odometry length, minus 1 (0 when the track is shorter)
};

/// @brief Yaw + translation (4 DOF, z up) that best maps odometry positions `odom[k]` onto
/// reference positions `ref[k]` where `use[k]` (identity for none).
Pose3 fitYawTranslation(const std::vector<Eigen::Vector3d>& odom,
                        const std::vector<Eigen::Vector3d>& ref, const std::vector<char>& use);

/// @brief The agreement of paired positions (same size, in time order; odometry z up).
TrackAgreement trackAgreement(const std::vector<Eigen::Vector3d>& odom,
                              const std::vector<Eigen::Vector3d>& ref, double scale_window);

}  // namespace mapfuse::geo
