#pragma once
/// @file Monocular camera model of a vehicle (Song et al. 2023 §3.2): projection and tilting
/// of the near-ground plane (CameraCalib, GroundPlane: core/drive_records.hpp).
#include <Eigen/Core>
#include <optional>

#include "mapfuse/core/drive_records.hpp"
#include "mapfuse/core/se3.hpp"

namespace mapfuse::vehicle {

/// @brief Projects a camera-frame point to pixels; nullopt when it is behind the camera
/// (z <= min_depth).
std::optional<Eigen::Vector2d> projectPoint(const Eigen::Matrix3d& K, const Eigen::Vector3d& p_cam,
                                            double min_depth = 1e-6);

/// @brief Rotates a ground normal by a camera pitch error (about the camera x axis) and a
/// roll error (about the camera z axis): n' = R_x(pitch) R_z(roll) n. Angles in rad.
Eigen::Vector3d tiltNormal(const Eigen::Vector3d& normal_cam, double pitch, double roll);

}  // namespace mapfuse::vehicle
