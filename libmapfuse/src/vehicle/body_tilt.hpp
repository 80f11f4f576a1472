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

/// @brief Per frame, the rotation (body frame) that takes the body's up axis e_z to the road
/// normal, the mean of the body's up axes (odom frame) of the frames within ±window/2 s.
/// @param T_odom_body ego-motion pose per frame
/// @param stamps s per frame (non-decreasing, same size)
/// @param window s; <= 0 gives identities
/// @throws InputError when the sizes differ or the stamps go backwards.
std::vector<Eigen::Matrix3d> roadTiltInBody(const std::vector<Pose3>& T_odom_body,
                                            const std::vector<double>& stamps, double window);

/// @brief The nominal camera-frame ground normal (level body) tilted by a body-frame rotation:
/// R_cam_body · R_tilt · R_body_cam · n.
Eigen::Vector3d tiltByBodyRotation(const Eigen::Vector3d& normal_cam, const Eigen::Matrix3d& R_tilt,
                                   const Eigen::Matrix3d& R_body_cam);

}  // namespace mapfuse::vehicle
