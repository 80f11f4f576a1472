#include "body_tilt.hpp"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <cmath>

#include "mapfuse/core/error.hpp"

namespace mapfuse::vehicle {
namespace {
/// Weight of a frame dt seconds from the window's centre.
double windowWeight(double dt, double window, TiltWeighting weighting) {
  if (weighting == TiltWeighting::kBox) return 1.0;
  const double c = std::cos(M_PI * dt / window);
  return c * c;
}

/// Value at frame i of the weighted least-squares quadratic in time through the body's up axes
/// (odom frame) of frames [lo, hi): unbiased where the road's pitch changes quadratically in
/// time, where the weighted mean is off by the curvature of the pitch profile over the window.
Eigen::Vector3d localQuadratic(const std::vector<Pose3>& T_odom_body,
                               const std::vector<double>& stamps, std::size_t i, std::size_t lo,
                               std::size_t hi, double window, TiltWeighting weighting) {
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d B = Eigen::Matrix3d::Zero();  // rows: 1, t, t²; columns: the up axis
  for (std::size_t j = lo; j < hi; ++j) {
    const double t = (stamps[j] - stamps[i]) / window;  // scaled: A stays well conditioned
    const double w = windowWeight(stamps[j] - stamps[i], window, weighting);
    const Eigen::Vector3d row(1.0, t, t * t);
    A += w * row * row.transpose();
    B += w * row * T_odom_body[j].linear().col(2).transpose();
  }
  const Eigen::Matrix3d coef = A.ldlt().solve(B);
  if (!coef.allFinite() || std::abs(A.determinant()) < 1e-12)
    return T_odom_body[i].linear().col(2);  // too few frames for a quadratic
  return coef.row(0).transpose();
}
}  // namespace

std::vector<Eigen::Matrix3d> roadTiltInBody(const std::vector<Pose3>& T_odom_body,
                                            const std::vector<double>& stamps, double window,
                                            TiltWeighting weighting,
                                            const std::vector<bool>& quadratic) {
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
    if (i < quadratic.size() && quadratic[i]) {
      road_odom = localQuadratic(T_odom_body, stamps, i, lo, hi, window, weighting);
    } else if (weighting == TiltWeighting::kBox) {
      road_odom = prefix[hi] - prefix[lo];
    } else {
      for (std::size_t j = lo; j < hi; ++j)
        road_odom +=
            windowWeight(stamps[j] - stamps[i], window, weighting) * T_odom_body[j].linear().col(2);
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
