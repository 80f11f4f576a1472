#pragma once
/// @file Which vanishing points the ground calibration may trust (issue 21). A vanishing point
/// gives the road plane only when the lane lines are straight and parallel to each other: lines
/// fitted to a curve or a merge meet off the horizon, and a median over a drive keeps that bias
/// (+0.0024 rad on a wide curved merge, 3 % of range at 15-25 m). The ego-motion tells which
/// frames look down a straight road: the heading must not turn, nor the pitch change (a crest or a
/// sag bends the lines out of the plane under the car), over the look-ahead (the
/// vp_max_range metres the lines are fitted over), and the lines' vanishing direction must have
/// the azimuth of the motion over that look-ahead (lines parallel to the motion vanish on its
/// image). Accepted frames are then pooled; with too few of them, or a median correction that is
/// not significant against its spread, the static extrinsic is kept.
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "mapfuse/core/drive_records.hpp"
#include "mapfuse/core/se3.hpp"
#include "mapfuse/vehicle/vanishing_point.hpp"

namespace mapfuse::vehicle {

/// The ego-motion ahead of one frame, over a fixed path length.
struct LookAhead {
  bool valid = false;           ///< false when the drive ends before the look-ahead
  double heading_change = 0.0;  ///< rad, largest |yaw| of the body ahead relative to the frame
  double pitch_change = 0.0;    ///< rad, the road's grade change over the look-ahead (|2 a D|)
  Eigen::Vector3d direction_body = Eigen::Vector3d::UnitX();  ///< unit chord, body frame
};

/// @brief Per frame, the motion over the next `distance` metres of path: the largest heading
/// change (yaw in the frame's body x-y plane), the grade change of the path (a parabola fitted to
/// its heights: a crest or a sag, not the body's rocking) and the chord direction in the body
/// frame.
std::vector<LookAhead> lookAheadMotion(const std::vector<Pose3>& T_odom_body, double distance);

/// @brief Signed angle (rad) from a to b about the unit normal n, both projected on the plane
/// perpendicular to n: the azimuth difference of two directions in the road plane.
double azimuthDifference(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                         const Eigen::Vector3d& n);

/// What the gate kept and decided (lsm-build.summary.json "vp_calibration").
struct VpCalibration {
  std::vector<double> corrections;  ///< rad per frame, applied (all 0 when fallen back)
  int estimates = 0;                ///< frames with a vanishing point
  int rejected_curve = 0;           ///< ... whose heading turns over the look-ahead
  int rejected_vertical_curve = 0;  ///< ... whose pitch changes over it (a crest or a sag)
  int rejected_no_look_ahead = 0;   ///< ... too near the drive's end to know
  int rejected_azimuth = 0;         ///< ... whose VP disagrees with the ego-motion direction
  int accepted = 0;                 ///< supporting frames
  double median = 0.0;              ///< rad, median correction of the accepted frames
  double spread = 0.0;              ///< rad, robust sigma (1.4826 MAD) of the accepted frames
  double standard_error = 0.0;      ///< rad, 1.2533 spread / sqrt(accepted)
  double azimuth_offset = 0.0;      ///< rad, median VP-vs-motion azimuth (a constant mount yaw)
  bool fallback = false;            ///< true: the static extrinsic is kept
  std::string fallback_reason;      ///< "", "too few frames", "not significant"
};

/// @brief Gates the per-frame estimates (straight look-ahead, VP azimuth within
/// max_azimuth_error of the motion after the median offset), decides between the pooled
/// correction and the static extrinsic, and smooths the accepted frames over `window`.
/// @param estimates per frame (nullopt: no vanishing point)
/// @param motion per frame, lookAheadMotion over settings.max_range
/// @param normals_cam per frame, the (tilted) nominal ground normal the estimates refer to
/// @param R_cam_body rotation of body vectors into the camera frame
VpCalibration gateVanishingPoints(const std::vector<std::optional<VanishingEstimate>>& estimates,
                                  const std::vector<LookAhead>& motion,
                                  const std::vector<Eigen::Vector3d>& normals_cam,
                                  const Eigen::Matrix3d& R_cam_body,
                                  const VanishingSettings& settings);

}  // namespace mapfuse::vehicle
