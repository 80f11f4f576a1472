#pragma once
/// @file Monocular camera model of a vehicle (Song et al. 2023 §3.2): pinhole intrinsics,
/// camera-to-body extrinsics and the near-ground plane in the camera frame.
#include <Eigen/Core>
#include <optional>

#include "mapfuse/core/se3.hpp"

namespace mapfuse::vehicle {

/// The near-ground plane in the camera frame: n^T X + h = 0, n unit and pointing up (away
/// from the road, towards the camera), h > 0 the camera height above the road.
struct GroundPlane {
  Eigen::Vector3d normal_cam{0.0, -1.0, 0.0};  ///< unit, camera frame (x right, y down, z fwd)
  double height = 1.5;                         ///< m, camera centre above the plane
};

/// Calibration of one camera (docs/formats-frames.md "calibration").
struct CameraCalib {
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();  ///< pinhole intrinsics, px
  int width = 0;                                    ///< px
  int height = 0;                                   ///< px
  Pose3 T_body_cam = Pose3::Identity();             ///< camera pose in the body frame
  GroundPlane ground;                               ///< nominal ground plane
  /// Camera of a poses file (KITTI: rectified camera 0) in this camera frame; identity when
  /// the poses file describes this camera itself.
  Pose3 T_cam_posecam = Pose3::Identity();
  /// KITTI only: the Velodyne in the poses-file camera (T_rect0_velo = R_rect_00 T_cam0_velo),
  /// to read LiDAR (T_world_velo) poses files; unset (false) for other inputs.
  Pose3 T_posecam_velo = Pose3::Identity();
  bool has_velo = false;  ///< T_posecam_velo is known
};

/// @brief Rotation taking camera axes (x right, y down, z forward) to body axes
/// (x forward, y left, z up) for a level, forward-looking camera.
Eigen::Matrix3d levelCameraToBodyRotation();

/// @brief Projects a camera-frame point to pixels; nullopt when it is behind the camera
/// (z <= min_depth).
std::optional<Eigen::Vector2d> projectPoint(const Eigen::Matrix3d& K, const Eigen::Vector3d& p_cam,
                                            double min_depth = 1e-6);

/// @brief Rotates a ground normal by a camera pitch error (about the camera x axis) and a
/// roll error (about the camera z axis): n' = R_x(pitch) R_z(roll) n. Angles in rad.
Eigen::Vector3d tiltNormal(const Eigen::Vector3d& normal_cam, double pitch, double roll);

}  // namespace mapfuse::vehicle
