#include "mapfuse/lidar/frame_fusion.hpp"

#include <algorithm>
#include <chrono>

#include "mapfuse/core/error.hpp"

namespace mapfuse::lidar {
namespace {
double seconds(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}
void checkSize(const io::SemanticImage& sem, const ImageProjection& camera) {
  if (sem.width != camera.width || sem.height != camera.height)
    throw InputError("semantics image is " + std::to_string(sem.width) + "x" +
                     std::to_string(sem.height) + ", image_02 is " + std::to_string(camera.width) +
                     "x" + std::to_string(camera.height));
}
}  // namespace

LabeledProjection labelScan(const std::vector<Eigen::Vector3f>& scan_velo,
                            const ImageProjection& camera, const io::SemanticImage& sem,
                            const ProjectionSettings& s) {
  checkSize(sem, camera);
  const ProjectedPoints pr = projectScan(scan_velo, camera, s);
  LabeledProjection out;
  out.points.reserve(pr.size());
  out.labels.reserve(pr.size());
  out.scan_index = pr.point_index;
  for (std::size_t k = 0; k < pr.size(); ++k) {
    out.points.push_back(scan_velo[pr.point_index[k]]);
    out.labels.push_back(pixelLabel(sem, pr.u[k], pr.v[k]));
  }
  return out;
}

FrameFusionStats fuseFrame(SemanticVoxelMap& map, const std::vector<Eigen::Vector3f>& scan_velo,
                           const Pose3& T_map_velo, const ImageProjection& camera,
                           const io::SemanticImage& sem, const ClusterClassifier& classifier,
                           const FrameFusionSettings& s) {
  using Clock = std::chrono::steady_clock;
  FrameFusionStats st;
  st.points = scan_velo.size();
  checkSize(sem, camera);
  // Coordinate alignment, eq. (2)-(3).
  const auto t0 = Clock::now();
  const ProjectedPoints pr = projectScan(scan_velo, camera, s.projection);
  st.projected = pr.size();
  std::vector<Eigen::Vector3f> pts(pr.size());
  std::vector<uint8_t> labels(pr.size());
  for (std::size_t k = 0; k < pr.size(); ++k) {
    pts[k] = scan_velo[pr.point_index[k]];
    labels[k] = pixelLabel(sem, pr.u[k], pr.v[k]);
  }
  const auto t1 = Clock::now();
  // Error minimisation, eq. (4) + forests.
  const std::vector<uint8_t> keep =
      minimizeErrors(pts, labels, classifier, s.clustering, &st.error_min);
  const auto t2 = Clock::now();
  // Fusion, eq. (5)-(6): one averaged measurement per voxel and frame.
  const std::size_t before = map.size();
  const Eigen::Matrix3f R = T_map_velo.linear().cast<float>();
  const Eigen::Vector3f t = T_map_velo.translation().cast<float>();
  std::vector<std::pair<uint32_t, uint32_t>> vk;  // (voxel index, projected index)
  vk.reserve(pr.size());
  for (std::size_t k = 0; k < pr.size(); ++k) {
    if (!keep[k]) continue;
    const Eigen::Vector3d p = (R * pts[k] + t).cast<double>();
    vk.emplace_back(static_cast<uint32_t>(map.findOrInsert(packKey(map.coordOf(p)))),
                    static_cast<uint32_t>(k));
  }
  st.fused_points = vk.size();
  std::sort(vk.begin(), vk.end());
  for (std::size_t b = 0; b < vk.size();) {
    std::size_t e = b;
    ClassDistribution avg{};
    while (e < vk.size() && vk[e].first == vk[b].first) {
      const std::size_t k = vk[e].second;
      const ClassDistribution d = pixelDistribution(sem, pr.u[k], pr.v[k], s.pixel);
      for (int c = 0; c < kNumLidarClasses; ++c) avg[c] += d[c];
      ++e;
    }
    const float inv = 1.0f / static_cast<float>(e - b);
    for (float& x : avg) x *= inv;
    map.fuse(vk[b].first, avg);
    ++st.fused_voxels;
    b = e;
  }
  st.new_voxels = map.size() - before;
  const auto t3 = Clock::now();
  st.t_projection = seconds(t0, t1);
  st.t_error_min = seconds(t1, t2);
  st.t_fusion = seconds(t2, t3);
  return st;
}

}  // namespace mapfuse::lidar
