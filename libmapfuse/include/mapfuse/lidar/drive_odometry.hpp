#pragma once
/// @file LiDAR odometry over the selected frames of a drive (lidar/scan_odometry.hpp), with the
/// untrusted-step policy of docs/lidar.md: every untrusted step is reported on stderr and in the
/// summary, and once more than `max_untrusted` steps are untrusted the run stops with an
/// InputError (exit 3) naming the frame, before the caller has written anything.
#include <nlohmann/json.hpp>
#include <vector>

#include "mapfuse/core/param.hpp"
#include "mapfuse/io/kitti_raw.hpp"
#include "mapfuse/lidar/scan_odometry.hpp"

namespace mapfuse::lidar {

struct DriveOdometrySettings {
  OdometrySettings odometry;
  int max_untrusted = 0;      ///< untrusted steps tolerated; one more stops the run
  double frame_period = 0.1;  ///< s between consecutive frame indices without timestamps

  /// The odometry parameters of lidar-semantic-map (the others keep OdometrySettings' values).
  template <class V>
  void visit(V& v) {
    using namespace param;
    v("odom_voxel_size", odometry.voxel_size, "m",
      "odometry local-map voxel (its nearest-neighbour reach; docs/lidar.md)", in(0.01, 10));
    v("odom_deskew", odometry.deskew, "", "constant-velocity de-skew of each sweep");
    v("odom_exclude_road_users", odometry.exclude_road_users, "",
      "leave low objects (road users) out of the odometry (geometric rule, docs/lidar.md; off: "
      "measured no better, and it drops nearby walls)");
    v("frame_period", frame_period, "s",
      "time between consecutive frame numbers of a drive without timestamps (KITTI: 0.1)",
      gt(0) & le(3600));
    v("odom_max_untrusted", max_untrusted, "",
      "untrusted odometry steps tolerated (listed in the summary); one more stops the run, exit 3",
      in(0, 1e9));
  }
};

struct DriveOdometryResult {
  std::vector<Pose3> T_odom_velo;  ///< one per selected frame (odom = first frame's velo)
  std::vector<OdometryStep> steps;
  std::vector<int> frame_index;  ///< frame number of each pose
  double seconds = 0.0;          ///< wall time of the registration (scan reading included)
};

/// @brief Time between two frames: timestamps when both are known, else the index gap times
/// `frame_period`.
double frameInterval(const io::KittiRawFrame& prev, const io::KittiRawFrame& cur,
                     double frame_period);

/// @brief Runs the odometry over `drive.frames`.
/// @throws InputError naming the frame when more than max_untrusted steps are untrusted;
/// IoError / ParseError from the scans.
DriveOdometryResult runDriveOdometry(const io::KittiRawDrive& drive,
                                     const DriveOdometrySettings& settings);

/// @brief Summary block: converged and trusted steps (frame 0 is not a step), travelled
/// distance, untrusted steps with their reasons, and per step frame, convergence, iterations,
/// inlier share, rmse, threshold, speed, constraint and trust.
nlohmann::json odometryReport(const DriveOdometryResult& result,
                              const DriveOdometrySettings& settings);

}  // namespace mapfuse::lidar
