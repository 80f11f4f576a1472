#pragma once
/// @file The simulated vehicle camera (docs/simulate.md "Camera"): pinhole, no distortion,
/// mounted at (x, y, z) in the body frame, looking forward and pitched down by `pitch`.
#include <Eigen/Core>
#include <optional>

#include "mapfuse/core/param.hpp"
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

  template <class V>
  void visit(V& v) {
    using namespace param;
    // frames masks hold width * height pixels
    v("camera_width", width, "px", "image width", in(1, 10000));
    v("camera_height", height, "px", "image height", in(1, 10000));
    v("camera_fx", fx, "px", "focal length x", gt(0) & le(1e6));
    v("camera_fy", fy, "px", "focal length y", gt(0) & le(1e6));
    v("camera_cx", cx, "px", "principal point x", in(-1e5, 1e5));
    v("camera_cy", cy, "px", "principal point y", in(-1e5, 1e5));
    v("camera_x", x, "m", "camera position in the body frame, forward", in(-100, 100));
    v("camera_y", y, "m", "camera position in the body frame, left", in(-100, 100));
    v("camera_z", z, "m", "camera height above the road", gt(0.3) & le(100));
    v("camera_pitch", pitch, "rad", "downward pitch of the optical axis", in(-1.5, 1.5));
    v("camera_min_range", min_range, "m", "closest ground point used", gt(0) & le(10000));
    v("camera_max_range", max_range, "m", "farthest element observed", gt(0) & le(10000));
    v.relation("camera_max_range", max_range, max_range > min_range, "> camera_min_range");
  }
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
