#include "mapfuse/lidar/projection.hpp"

#include <cmath>

namespace mapfuse::lidar {

bool projectPoint(const Eigen::Matrix<double, 3, 4>& P, const Eigen::Vector3d& p_velo, double* u,
                  double* v) {
  const Eigen::Vector3d h = P.leftCols<3>() * p_velo + P.col(3);  // eq. (2)
  if (h.z() <= 1e-9) return false;
  *u = h.x() / h.z();  // eq. (3)
  *v = h.y() / h.z();
  return true;
}

ImageProjection ImageProjection::of(const io::KittiCalibration& calib) {
  return {calib.veloToImage2(), calib.image_width, calib.image_height};
}

ProjectedPoints projectScan(const std::vector<Eigen::Vector3f>& points_velo,
                            const ImageProjection& camera, const ProjectionSettings& s) {
  ProjectedPoints out;
  out.point_index.reserve(points_velo.size() / 4);
  out.u.reserve(points_velo.size() / 4);
  out.v.reserve(points_velo.size() / 4);
  const Eigen::Matrix<float, 3, 4> Pf = camera.P.cast<float>();
  const float r2min = static_cast<float>(s.min_range * s.min_range);
  const float r2max = static_cast<float>(s.max_range * s.max_range);
  const float w = static_cast<float>(camera.width), hgt = static_cast<float>(camera.height);
  for (std::size_t i = 0; i < points_velo.size(); ++i) {
    const Eigen::Vector3f& p = points_velo[i];
    const float r2 = p.squaredNorm();
    if (r2 < r2min || r2 > r2max) continue;
    const Eigen::Vector3f h = Pf.leftCols<3>() * p + Pf.col(3);
    if (h.z() <= 1e-6f) continue;
    const float fu = h.x() / h.z() + 0.5f, fv = h.y() / h.z() + 0.5f;
    if (fu < 0.f || fv < 0.f || fu >= w || fv >= hgt) continue;
    out.point_index.push_back(static_cast<uint32_t>(i));
    out.u.push_back(static_cast<int32_t>(fu));
    out.v.push_back(static_cast<int32_t>(fv));
  }
  return out;
}

}  // namespace mapfuse::lidar
