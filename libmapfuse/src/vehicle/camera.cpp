#include "mapfuse/vehicle/camera.hpp"

#include <Eigen/Geometry>

namespace mapfuse::vehicle {

std::optional<Eigen::Vector2d> projectPoint(const Eigen::Matrix3d& K, const Eigen::Vector3d& p_cam,
                                            double min_depth) {
  if (!(p_cam.z() > min_depth)) return std::nullopt;
  const Eigen::Vector3d q = K * p_cam;
  return Eigen::Vector2d(q.x() / q.z(), q.y() / q.z());
}

Eigen::Vector3d tiltNormal(const Eigen::Vector3d& normal_cam, double pitch, double roll) {
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitX()) *
                             Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitZ()))
                                .toRotationMatrix();
  return (R * normal_cam).normalized();
}

}  // namespace mapfuse::vehicle
