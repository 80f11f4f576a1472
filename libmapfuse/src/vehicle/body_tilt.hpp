#pragma once
/// @file Body tilt against the road from the ego-motion. Eq. (1) ranges ground pixels on a plane
/// fixed to the camera; a body that pitches and rolls on its suspension (a few tenths of a degree
/// at ~1 Hz) moves that plane, and at 25 m a 0.01 rad pitch error moves a ranged point by
/// d²/h · 0.01 ≈ 4 m. The ego-motion sees the motion: the dead-reckoned attitude integrates the
/// gyro (poses from LiDAR odometry or OXTS carry it as well). The road's normal is taken as the
/// body's up axis averaged over a window of a few seconds (the suspension oscillates about it;
/// road grade and gyro drift change slowly), and each frame's plane is tilted by the rotation
/// from the body's own up axis to that average. The lane vanishing points (§3.2.1) then only
/// have to find what stays: a miscalibrated camera mount.
#include <Eigen/Core>
#include <vector>

#include "mapfuse/core/se3.hpp"

namespace mapfuse::vehicle {

/// How the frames of the window are weighted in the mean up axis.
enum class TiltWeighting {
  kBox,   ///< equal weights: a suspension oscillation leaks through at 1/(pi f W) of its amplitude
  kHann,  ///< cos^2 taper: above 2/W Hz the leak is below 3 % (-31 dB sidelobes, 1/f^3 decay)
};

/// @brief Per frame, the rotation (body frame) that takes the body's up axis e_z to the road
/// normal, the weighted mean of the body's up axes (odom frame) of the frames within ±window/2 s.
/// A box window of 2 s leaves 22 % of a 0.7 Hz pitch oscillation (sin(pi f W)/(pi f W)); a Hann
/// window of 4 s leaves 1 % (H(x) = sinc(x)/(1 - x^2), x = f W) and follows grade as a ~2 s box.
/// @param T_odom_body ego-motion pose per frame
/// @param stamps s per frame (non-decreasing, same size)
/// @param window s; <= 0 gives identities
/// @param quadratic per frame (or empty): take the road normal as the value at the frame of a
/// weighted least-squares quadratic in time through the up axes, not their mean: where the road's
/// pitch bends within the window (a short steep crest: esmini crest-curve, 6 m over 140 m) the
/// mean is off by 0.007-0.016 rad and the quadratic by ~0.002; on an even road the quadratic
/// lets the suspension through (flat world: 0.0018 against 0.0005 rad), so only frames that the
/// path shows on a sharp vertical curve take it (path_surface.hpp, sharpVerticalCurves).
/// @throws InputError when the sizes differ or the stamps go backwards.
std::vector<Eigen::Matrix3d> roadTiltInBody(const std::vector<Pose3>& T_odom_body,
                                            const std::vector<double>& stamps, double window,
                                            TiltWeighting weighting = TiltWeighting::kBox,
                                            const std::vector<bool>& quadratic = {});

/// @brief Camera height above the road once the body is tilted by R_tilt (body frame), the body
/// pivoting about its origin (the origin keeps its height above the road): the camera, t_body_cam
/// from the origin, moves by (R_tilt n - n) . t_body_cam, n the nominal road normal in the body
/// frame. The simulator's body pivots about its origin on the road with the camera 1.8 m ahead:
/// a 0.01 rad pitch moves the 1.4 m high camera by 0.018 m, 1.3 % of every ground range.
double tiltedCameraHeight(double nominal_height, const Eigen::Vector3d& normal_cam,
                          const Eigen::Matrix3d& R_tilt, const Pose3& T_body_cam);

/// @brief The nominal camera-frame ground normal (level body) tilted by a body-frame rotation:
/// R_cam_body · R_tilt · R_body_cam · n.
Eigen::Vector3d tiltByBodyRotation(const Eigen::Vector3d& normal_cam, const Eigen::Matrix3d& R_tilt,
                                   const Eigen::Matrix3d& R_body_cam);

}  // namespace mapfuse::vehicle
