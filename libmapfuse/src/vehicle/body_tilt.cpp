#include "body_tilt.hpp"

#include <Eigen/Geometry>
#include <cmath>

#include "mapfuse/core/error.hpp"

namespace mapfuse::vehicle {

std::vector<Eigen::Matrix3d> roadTiltInBody(const std::vector<Pose3>& T_odom_body,
                                            const std::vector<double>& stamps, double window,
                                            TiltWeighting weighting) {
  const std::size_t n = T_odom_body.size();
  if (stamps.size() != n)
    throw InputError("body tilt: " + std::to_string(stamps.size()) + " stamps for " +
                     std::to_string(n) + " poses");
  for (std::size_t i = 1; i < n; ++i)
    if (stamps[i] < stamps[i - 1])
      throw InputError("body tilt: frame stamps go backwards at frame " + std::to_string(i));
  std::vector<Eigen::Matrix3d> out(n, Eigen::Matrix3d::Identity());
  if (!(window > 0) || n == 0) return out;
  // Prefix sums of the body's up axis in the odom frame; two pointers bound the window.
  std::vector<Eigen::Vector3d> prefix(n + 1, Eigen::Vector3d::Zero());
  for (std::size_t i = 0; i < n; ++i) prefix[i + 1] = prefix[i] + T_odom_body[i].linear().col(2);
  std::size_t lo = 0, hi = 0;  // frames [lo, hi) lie within the window around frame i
  for (std::size_t i = 0; i < n; ++i) {
    while (stamps[lo] < stamps[i] - 0.5 * window) ++lo;
    while (hi < n && stamps[hi] <= stamps[i] + 0.5 * window) ++hi;
    Eigen::Vector3d road_odom = Eigen::Vector3d::Zero();
    if (weighting == TiltWeighting::kBox) {
      road_odom = prefix[hi] - prefix[lo];
    } else {
      for (std::size_t j = lo; j < hi; ++j) {
        const double c = std::cos(M_PI * (stamps[j] - stamps[i]) / window);
        road_odom += c * c * T_odom_body[j].linear().col(2);
      }
    }
    road_odom.normalize();
    const Eigen::Vector3d road_body = T_odom_body[i].linear().transpose() * road_odom;
    out[i] =
        Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), road_body).toRotationMatrix();
  }
  return out;
}

double tiltedCameraHeight(double nominal_height, const Eigen::Vector3d& normal_cam,
                          const Eigen::Matrix3d& R_tilt, const Pose3& T_body_cam) {
  const Eigen::Vector3d n_body = T_body_cam.linear() * normal_cam;
  return nominal_height + (R_tilt * n_body - n_body).dot(T_body_cam.translation());
}

Eigen::Vector3d tiltByBodyRotation(const Eigen::Vector3d& normal_cam, const Eigen::Matrix3d& R_tilt,
                                   const Eigen::Matrix3d& R_body_cam) {
  return (R_body_cam.transpose() * R_tilt * R_body_cam * normal_cam).normalized();
}

}  // namespace mapfuse::vehicle
