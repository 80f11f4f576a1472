#include "road_occlusion.hpp"

#include <algorithm>

namespace mapfuse::sim {

RoadOcclusion::RoadOcclusion(const std::vector<Pose3>& T_enu_body, std::size_t step)
    : step_(std::max<std::size_t>(1, step)) {
  const std::size_t n = T_enu_body.size();
  T_body_enu_.resize(n);
  distance_.assign(n, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    T_body_enu_[k] = T_enu_body[k].inverse();
    if (k > 0)
      distance_[k] =
          distance_[k - 1] + (T_enu_body[k].translation() - T_enu_body[k - 1].translation()).norm();
  }
}

bool RoadOcclusion::hidden(std::size_t k, const Eigen::Vector3d& cam_enu,
                           const Eigen::Vector3d& p_enu, double max_distance) const {
  const Eigen::Vector3d ray = p_enu - cam_enu;
  for (std::size_t j = k + step_; j < T_body_enu_.size(); j += step_) {
    if (distance_[j] - distance_[k] > max_distance) break;
    // The sight line cam + λ ray in body j: where it passes abreast of the pose (x = 0).
    const Eigen::Vector3d a = T_body_enu_[j] * cam_enu;
    const Eigen::Vector3d b = T_body_enu_[j].linear() * ray;
    if (!(std::abs(b.x()) > 1e-9)) continue;
    const double lambda = -a.x() / b.x();
    if (lambda <= 0.0) continue;  // the pose lies behind the camera along this line
    if (lambda >= 1.0) break;     // the point itself is before this pose
    if (a.z() + lambda * b.z() < -kOcclusionTolerance) return true;
  }
  return false;
}

}  // namespace mapfuse::sim
