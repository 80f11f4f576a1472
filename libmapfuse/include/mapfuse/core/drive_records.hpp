#pragma once
/// @file What a recorded drive holds for lsm-build (docs/formats-frames.md): the camera
/// calibration with its nominal ground plane, IMU and wheel samples, and the per-frame
/// perception output (observations.jsonl, or derived from masks / the fallback perception).
/// Plain data: io reads and writes it, vehicle/ computes with it (Song et al. 2023 §3).
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "mapfuse/core/classes.hpp"
#include "mapfuse/core/se3.hpp"

namespace mapfuse {

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
inline Eigen::Matrix3d levelCameraToBodyRotation() {
  Eigen::Matrix3d R;
  // Columns: camera x (right) = -body y, camera y (down) = -body z, camera z (fwd) = body x.
  R << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  return R;
}

struct ImuSample {
  double stamp = 0.0;                               ///< s
  Eigen::Vector3d gyro = Eigen::Vector3d::Zero();   ///< rad/s, body frame
  Eigen::Vector3d accel = Eigen::Vector3d::Zero();  ///< m/s^2, body frame (unused here)
};

struct WheelSample {
  double stamp = 0.0;  ///< s
  double speed = 0.0;  ///< m/s, forward
};

/// A ground marking seen in one frame: a centre line (lines) or a polygon ring (planar).
struct GroundObservation {
  CrowdClass cls = CrowdClass::kLaneLine;
  Attributes attributes;
  int64_t track_id = -1;  ///< stable across frames when known, -1 = associate spatially
  int64_t truth_id = -1;  ///< simulator only
  std::vector<Eigen::Vector2d> pixels;  ///< px, pixel centres at integer coordinates
};

/// An aerial element (sign, light, pole) seen in one frame.
struct AerialObservation {
  CrowdClass cls = CrowdClass::kTrafficSign;
  int64_t track_id = -1;  ///< -1 = associate by optical flow
  int64_t truth_id = -1;
  Eigen::Vector4d box = Eigen::Vector4d::Zero();  ///< u_min, v_min, u_max, v_max (px)
  /// Key points (px): sign 4 corners; light [bottom centre, top centre]; pole [base, top].
  /// Empty = use the box (centre for signs, bottom / top centre for lights and poles).
  std::vector<Eigen::Vector2d> points;
  double confidence = 1.0;  ///< detector confidence in [0, 1] (segmentation: mean probability)
  /// Detector of the box: 0 = the input or the segmentation network, 1 = colour cues
  /// (vehicle/aerial_colour.hpp); optical-flow tracks never join boxes of two detectors.
  int detector = 0;
};

/// Everything perceived in one camera frame.
struct FrameObservations {
  int index = 0;
  double stamp = 0.0;  ///< s
  std::vector<GroundObservation> ground;
  std::vector<AerialObservation> aerial;
};

}  // namespace mapfuse
