#include "mapfuse/lidar/scan_odometry.hpp"

#include <cmath>

#include "mapfuse/core/error.hpp"
#include "mapfuse/fusion/gicp.hpp"

namespace mapfuse::lidar {

double sweepFraction(const Eigen::Vector3f& p) {
  return 0.5 * (-std::atan2(double(p.y()), double(p.x())) / M_PI + 1.0);
}

std::vector<Eigen::Vector3d> deskewScan(const std::vector<Eigen::Vector3f>& scan,
                                        const Pose3& motion) {
  const Vector6d xi = logSE3(motion);
  std::vector<Eigen::Vector3d> out(scan.size());
  for (std::size_t i = 0; i < scan.size(); ++i)
    out[i] = expSE3((sweepFraction(scan[i]) - 0.5) * xi) * scan[i].cast<double>();
  return out;
}

ScanOdometry::ScanOdometry(const OdometrySettings& s) : s_(s) {
  if (!(s.voxel_size > 0) || s.local_map_scans < 1 || !(s.fine_correspondence > 0) ||
      !(s.coarse_correspondence >= s.fine_correspondence) || s.max_iterations < 1)
    throw ConfigError(
        "odometry settings invalid (voxel > 0, local map >= 1, "
        "coarse >= fine correspondence > 0, iterations >= 1)");
}

fusion::Cloud ScanOdometry::preprocess(const std::vector<Eigen::Vector3f>& scan,
                                       const Pose3& motion) const {
  fusion::Cloud raw;
  raw.points.reserve(scan.size());
  const double r2min = s_.min_range * s_.min_range, r2max = s_.max_range * s_.max_range;
  std::vector<Eigen::Vector3d> pts;
  if (s_.deskew)
    pts = deskewScan(scan, motion);
  else
    for (const auto& p : scan) pts.push_back(p.cast<double>());
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const double r2 = scan[i].cast<double>().squaredNorm();
    if (r2 >= r2min && r2 <= r2max) raw.points.push_back(pts[i]);
  }
  fusion::Cloud cloud = fusion::voxelDownsample(raw, s_.voxel_size);
  fusion::estimateCovariances(cloud, s_.covariance_neighbors, 4.0 * s_.voxel_size);
  return cloud;
}

Pose3 ScanOdometry::add(const std::vector<Eigen::Vector3f>& scan) {
  // Constant-velocity prediction from the last two poses.
  Pose3 motion = Pose3::Identity();
  if (poses_.size() >= 2) motion = poses_[poses_.size() - 2].inverse() * poses_.back();
  const fusion::Cloud source = preprocess(scan, motion);
  if (source.size() < 10) throw InputError("scan has fewer than 10 points after filtering");
  Pose3 T = poses_.empty() ? Pose3::Identity() : poses_.back() * motion;
  OdometryStep step;
  if (!recent_.empty()) {
    fusion::Cloud target_cloud;
    for (const auto& c : recent_) fusion::appendCloud(target_cloud, c);
    target_cloud = fusion::voxelDownsample(target_cloud, s_.voxel_size);
    fusion::estimateCovariances(target_cloud, s_.covariance_neighbors, 4.0 * s_.voxel_size);
    for (double dist : {s_.coarse_correspondence, s_.fine_correspondence}) {
      const fusion::GicpTarget target(target_cloud, dist);
      fusion::GicpSettings gs;
      gs.max_correspondence_distance = dist;
      gs.max_iterations = s_.max_iterations;
      gs.translation_eps = 1e-5;
      gs.rotation_eps = 1e-5;
      gs.num_threads = s_.num_threads;
      const fusion::GicpResult r = fusion::alignGicp(target, source, T, gs);
      T = r.T_target_source;
      step.converged = r.converged;
      step.iterations += r.iterations;
      step.num_inliers = r.num_inliers;
      step.rmse = r.rmse;
      step.fitness = r.fitness;
    }
  }
  poses_.push_back(T);
  steps_.push_back(step);
  recent_.push_back(fusion::transformCloud(source, T));
  while (static_cast<int>(recent_.size()) > s_.local_map_scans) recent_.pop_front();
  return T;
}

}  // namespace mapfuse::lidar
