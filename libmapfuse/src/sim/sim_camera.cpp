#include "mapfuse/sim/sim_camera.hpp"

namespace mapfuse::sim {

SimCamera::SimCamera(const CameraParams& p) : p_(p) {
  K_ << p.fx, 0, p.cx, 0, p.fy, p.cy, 0, 0, 1;
  Eigen::Matrix3d level;  // columns: camera x, y, z axes in body coordinates
  level.col(0) = Eigen::Vector3d(0, -1, 0);
  level.col(1) = Eigen::Vector3d(0, 0, -1);
  level.col(2) = Eigen::Vector3d(1, 0, 0);
  T_body_cam_ = Pose3::Identity();
  T_body_cam_.linear() =
      Eigen::AngleAxisd(p.pitch, Eigen::Vector3d::UnitY()).toRotationMatrix() * level;
  T_body_cam_.translation() = Eigen::Vector3d(p.x, p.y, p.z);
  T_cam_body_ = T_body_cam_.inverse();
}

Eigen::Vector3d SimCamera::groundNormalCam() const {
  return T_cam_body_.linear() * Eigen::Vector3d::UnitZ();
}

std::optional<Eigen::Vector2d> SimCamera::project(const Eigen::Vector3d& q,
                                                  double min_depth) const {
  if (q.z() < min_depth) return std::nullopt;
  return Eigen::Vector2d(p_.fx * q.x() / q.z() + p_.cx, p_.fy * q.y() / q.z() + p_.cy);
}

bool SimCamera::sees(const Eigen::Vector3d& p_body, double min_depth) const {
  const Eigen::Vector3d q = T_cam_body_ * p_body;
  if (q.norm() > p_.max_range) return false;
  const auto uv = project(q, min_depth);
  return uv && uv->x() >= -0.5 && uv->y() >= -0.5 && uv->x() <= p_.width - 0.5 &&
         uv->y() <= p_.height - 0.5;
}

}  // namespace mapfuse::sim
