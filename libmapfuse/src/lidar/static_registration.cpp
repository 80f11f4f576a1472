#include "mapfuse/lidar/static_registration.hpp"

#include "mapfuse/fusion/gicp.hpp"

namespace mapfuse::lidar {
namespace {

fusion::Cloud staticCloud(const std::vector<Eigen::Vector3f>& scan,
                          const StaticRegistrationSettings& s) {
  std::vector<Eigen::Vector3d> pts;
  pts.reserve(scan.size());
  for (const auto& p : scan) {
    const double r = p.cast<double>().norm();
    if (r >= s.min_range && r <= s.max_range) pts.push_back(p.cast<double>());
  }
  std::vector<double> h;
  const auto kinds = splitScanGeometry(pts, s.geometry, nullptr, &h);
  fusion::Cloud c;
  for (std::size_t i = 0; i < pts.size(); ++i)
    if (kinds[i] == ScanPointKind::kStatic && h[i] >= s.min_height) c.points.push_back(pts[i]);
  c = fusion::voxelDownsample(c, s.voxel_size);
  fusion::estimateCovariances(c, 10, 4.0 * s.voxel_size);
  return c;
}

}  // namespace

Pose3 registerStaticStructure(const std::vector<Eigen::Vector3f>& scan_a,
                              const std::vector<Eigen::Vector3f>& scan_b, const Pose3& init,
                              const StaticRegistrationSettings& s, double* fitness) {
  const fusion::Cloud a = staticCloud(scan_a, s), b = staticCloud(scan_b, s);
  Pose3 T = init;
  fusion::GicpResult r;
  for (double dist : {2.0, 1.0, 0.5, 0.25}) {  // coarse to fine correspondence distances (m)
    fusion::GicpSettings gs;
    gs.max_correspondence_distance = dist;
    gs.max_iterations = 100;
    gs.translation_eps = 1e-6;
    gs.rotation_eps = 1e-6;
    r = fusion::alignGicp(fusion::GicpTarget(a, dist), b, T, gs);
    T = r.T_target_source;
  }
  if (fitness) *fitness = r.fitness;
  return T;
}

}  // namespace mapfuse::lidar
