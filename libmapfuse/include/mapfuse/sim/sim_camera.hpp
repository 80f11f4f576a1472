#pragma once
/// @file The simulated vehicle camera (docs/simulate.md "Camera"): pinhole, no distortion,
/// mounted at (x, y, z) in the body frame, looking forward and pitched down by `pitch`.
#include <Eigen/Core>
#include <optional>

#include "mapfuse/core/se3.hpp"

namespace mapfuse::sim {

struct CameraParams {
  int width = 1280;         ///< px
  int height = 720;         ///< px
  double fx = 1000.0;       ///< px
  double fy = 1000.0;       ///< px
  double cx = 639.5;        ///< px
  double cy = 359.5;        ///< px
  double x = 1.8;           ///< m, camera centre in the body frame (forward)
  double y = 0.0;           ///< m (left)
  double z = 1.4;           ///< m (up) = camera height above the road
  double pitch = 0.035;     ///< rad, downward pitch of the optical axis
  double min_range = 4.0;   ///< m, closest ground point used (from the camera)
  double max_range = 40.0;  ///< m, farthest element observed (from the camera)
};

class SimCamera {
 public:
  explicit SimCamera(const CameraParams& params);
  const CameraParams& params() const { return p_; }
  const Eigen::Matrix3d& K() const { return K_; }
  const Pose3& T_body_cam() const { return T_body_cam_; }
  /// @brief Unit ground normal in the camera frame for a level body (points up).
  Eigen::Vector3d groundNormalCam() const;
  /// @brief Pixel of a camera-frame point; nullopt when its depth is below `min_depth`.
  std::optional<Eigen::Vector2d> project(const Eigen::Vector3d& p_cam,
                                         double min_depth = 1.0) const;
  /// @brief True when the body-frame point projects inside the image with depth in
  /// [min_depth, max_range].
  bool sees(const Eigen::Vector3d& p_body, double min_depth) const;

 private:
  CameraParams p_;
  Eigen::Matrix3d K_;
  Pose3 T_body_cam_;
  Pose3 T_cam_body_;
};

}  // namespace mapfuse::sim
