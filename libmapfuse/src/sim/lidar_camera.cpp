#include "mapfuse/sim/lidar_camera.hpp"

#include <algorithm>
#include <cmath>

namespace mapfuse::sim {

CameraFrame renderLabels(const LidarScene& scene, const io::KittiCalibration& calib,
                         const Pose3& T_world_velo, double time, double max_range) {
  CameraFrame f;
  f.width = calib.image_width;
  f.height = calib.image_height;
  const std::size_t n = static_cast<std::size_t>(f.width) * f.height;
  f.labels.assign(n, 0);
  f.depth.assign(n, 0.f);
  // P_rect_02 = K [I | t]: camera 2's centre in the rectified camera-0 frame is -K^-1 P(:,3).
  const Eigen::Matrix3d K = calib.P_rect_02.leftCols<3>();
  const Eigen::Matrix3d Kinv = K.inverse();
  const Eigen::Vector3d centre_rect = -(Kinv * calib.P_rect_02.col(3));
  const Pose3 T_world_rect = T_world_velo * calib.T_rect0_velo().inverse();
  const Eigen::Vector3d o = T_world_rect * centre_rect;
  const Eigen::Matrix3d R = T_world_rect.linear();
  const std::vector<Primitive> dynamic = scene.dynamicAt(time);
#pragma omp parallel for schedule(dynamic, 4)
  for (int v = 0; v < f.height; ++v) {
    for (int u = 0; u < f.width; ++u) {
      const Eigen::Vector3d d = (R * (Kinv * Eigen::Vector3d(u, v, 1.0))).normalized();
      const RayHit hit = scene.cast(o, d, max_range, dynamic);
      if (!hit.hit()) continue;
      const std::size_t i = static_cast<std::size_t>(v) * f.width + u;
      f.labels[i] = static_cast<uint8_t>(hit.label.cls);
      f.depth[i] = static_cast<float>(hit.t);
    }
  }
  return f;
}

std::vector<uint8_t> shadeLabels(const CameraFrame& f) {
  const std::size_t n = static_cast<std::size_t>(f.width) * f.height;
  std::vector<uint8_t> bgr(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    if (f.depth[i] <= 0.f) {  // sky
      bgr[3 * i] = 235, bgr[3 * i + 1] = 206, bgr[3 * i + 2] = 135;
      continue;
    }
    const auto c = lidarClassColor(static_cast<LidarClass>(f.labels[i]));
    const double shade = 0.35 + 0.65 * std::exp(-f.depth[i] / 60.0);
    for (int k = 0; k < 3; ++k)
      bgr[3 * i + k] = static_cast<uint8_t>(std::lround(c[2 - k] * shade));
  }
  return bgr;
}

bool projectToImage2(const io::KittiCalibration& calib, const Eigen::Vector3d& p_velo, double& u,
                     double& v) {
  const Eigen::Vector3d q = calib.veloToImage2() * p_velo.homogeneous();
  if (q.z() <= 0.0) return false;
  u = q.x() / q.z();
  v = q.y() / q.z();
  return true;
}

}  // namespace mapfuse::sim
