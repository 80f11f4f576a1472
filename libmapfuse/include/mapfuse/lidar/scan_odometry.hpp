#pragma once
/// @file LiDAR odometry by scan-to-map registration with the project's GICP
/// (fusion/gicp.hpp): constant-velocity prediction, a local map of the most recent scans,
/// coarse-to-fine correspondence distances, optional constant-velocity de-skew.
#include <Eigen/Core>
#include <deque>
#include <vector>

#include "mapfuse/core/se3.hpp"
#include "mapfuse/fusion/point_cloud.hpp"

namespace mapfuse::lidar {

struct OdometrySettings {
  double voxel_size = 0.25;            ///< m, source and local-map downsampling
  double min_range = 3.0;              ///< m, drops the ego vehicle
  double max_range = 80.0;             ///< m
  int local_map_scans = 10;            ///< recent registered scans forming the target
  double coarse_correspondence = 2.0;  ///< m, first GICP pass
  double fine_correspondence = 0.5;    ///< m, second GICP pass
  int max_iterations = 50;             ///< per pass
  int covariance_neighbors = 10;       ///< k of the GICP covariances
  bool deskew = false;                 ///< constant-velocity motion compensation of each sweep
  int num_threads = 1;                 ///< OpenMP threads inside GICP
};

/// Registration quality of one scan.
struct OdometryStep {
  bool converged = true;
  int iterations = 0;
  int num_inliers = 0;
  double rmse = 0.0;  ///< m
  double fitness = 0.0;
};

class ScanOdometry {
 public:
  explicit ScanOdometry(const OdometrySettings& settings);

  /// @brief Registers the next scan (Velodyne frame) to the local map.
  /// @return T_odom_velo of the scan (odom = the first scan's Velodyne frame); with de-skew the
  /// pose is that of the sweep's middle.
  Pose3 add(const std::vector<Eigen::Vector3f>& scan_velo);

  const std::vector<Pose3>& poses() const { return poses_; }
  const std::vector<OdometryStep>& steps() const { return steps_; }

 private:
  fusion::Cloud preprocess(const std::vector<Eigen::Vector3f>& scan, const Pose3& motion) const;
  OdometrySettings s_;
  std::vector<Pose3> poses_;
  std::vector<OdometryStep> steps_;
  std::deque<fusion::Cloud> recent_;  ///< downsampled scans in the odom frame
};

/// @brief kiss-icp's KITTI convention for the relative time of a point within its sweep:
/// s = 0.5 * (-atan2(y, x) / pi + 1) in [0, 1], 0.5 = looking forward.
double sweepFraction(const Eigen::Vector3f& p);

/// @brief Constant-velocity de-skew: p' = exp((s - 0.5) * log(motion)) p, with `motion`
/// T_prev_current of the previous step (one sweep).
std::vector<Eigen::Vector3d> deskewScan(const std::vector<Eigen::Vector3f>& scan,
                                        const Pose3& motion);

}  // namespace mapfuse::lidar
