#pragma once
/// @file LiDAR odometry (docs/lidar.md, "Odometry"), after kiss-icp (Vizzo et al. 2023): each
/// sweep is de-skewed with the constant-velocity motion, optionally stripped of possible road users
/// (lidar/scan_geometry.hpp), thinned, and registered point-to-plane to a bounded local voxel map
/// (lidar/local_voxel_map.hpp) with an adaptive correspondence threshold, then once more with a
/// fine one. The step is judged (lidar/odometry_trust.hpp); trusted sweeps that moved far enough
/// from the last keyframe enter the map. Keyframes keep the map's samples apart from the sweep
/// being registered: in slow traffic, a map of the last few sweeps holds nearly the same ring
/// pattern as the new one and pulls the estimate towards standing still. Poses are composed on
/// SE(3) and re-orthonormalised after every step.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "mapfuse/core/param.hpp"
#include "mapfuse/core/se3.hpp"
#include "mapfuse/lidar/local_voxel_map.hpp"
#include "mapfuse/lidar/map_registration.hpp"
#include "mapfuse/lidar/odometry_trust.hpp"
#include "mapfuse/lidar/scan_geometry.hpp"

namespace mapfuse::lidar {

struct OdometrySettings {
  double min_range = 3.0;           ///< m, drops the ego vehicle
  double max_range = 100.0;         ///< m, also the local map's radius
  double voxel_size = 1.0;          ///< m, local-map voxel (exact nearest-neighbour radius)
  int max_points_per_voxel = 10;    ///< local map (kiss-icp: 20; measured no better here)
  double scan_spacing = 0.5;        ///< m, the sweep is thinned to this spacing for the map
  double source_spacing = 1.0;      ///< m, and to this one for the registration
  int normal_neighbors = 10;        ///< k of the normals of keyframe points
  double normal_radius = 2.0;       ///< m, their search radius (spanning several rings)
  double keyframe_distance = 0.5;   ///< m moved since the last keyframe that makes a new one
  double keyframe_angle = 5.0;      ///< deg turned since the last keyframe that makes a new one
  bool deskew = true;               ///< constant-velocity motion compensation of each sweep
  double sweep_period = 0.1;        ///< s, one turn of the sensor (KITTI HDL-64E: 10 Hz)
  bool exclude_road_users = false;  ///< leave possible road users out (lidar/scan_geometry.hpp)
  SceneGeometrySettings geometry;   ///< the road-user rule
  double geometry_spacing = 0.2;    ///< m, the sweep is thinned to this spacing for the rule
  double initial_threshold = 2.0;   ///< m, sigma of the adaptive threshold before any motion
  double min_motion = 0.1;          ///< m, smaller model deviations do not adapt the threshold
  double fine_threshold = 0.5;      ///< m, correspondence threshold of the second pass
  MapRegistrationSettings registration;
  TrustSettings trust;

  /// Declares this struct's own rules; `geometry` and `trust` declare theirs (ScanOdometry
  /// checks all three).
  static constexpr const char* kName = "OdometrySettings";  ///< names the owner in messages
  template <class V>
  void visit(V& v) {
    using namespace param;
    v("min_range", min_range, "m", "closer returns are dropped", ge(0));
    v("max_range", max_range, "m", "farther returns are dropped", gt(0));
    v.relation("max_range", max_range, max_range > min_range, "> min_range");
    v("voxel_size", voxel_size, "m", "local-map voxel", gt(0));
    v("max_points_per_voxel", max_points_per_voxel, "", "local-map points per voxel", in(1, 255));
    v("scan_spacing", scan_spacing, "m", "thinning of the sweep for the map", gt(0));
    v("source_spacing", source_spacing, "m", "thinning of the sweep for the registration", gt(0));
    v.relation("source_spacing", source_spacing, source_spacing >= scan_spacing, ">= scan_spacing");
    v("normal_neighbors", normal_neighbors, "", "k of the keyframe normals", in(3, 32));
    v("normal_radius", normal_radius, "m", "search radius of the normals", gt(0));
    v("keyframe_distance", keyframe_distance, "m", "distance moved that makes a keyframe", ge(0));
    v("keyframe_angle", keyframe_angle, "deg", "angle turned that makes a keyframe", ge(0));
    v("deskew", deskew, "", "constant-velocity motion compensation");
    v("sweep_period", sweep_period, "s", "one turn of the sensor", gt(0));
    v("exclude_road_users", exclude_road_users, "", "leave possible road users out");
    v("geometry_spacing", geometry_spacing, "m", "thinning of the sweep for the road-user rule",
      gt(0));
    v("initial_threshold", initial_threshold, "m", "adaptive threshold before any motion", gt(0));
    v("min_motion", min_motion, "m", "smaller deviations do not adapt the threshold", ge(0));
    v("fine_threshold", fine_threshold, "m", "correspondence threshold of the second pass", gt(0));
    v("registration.max_iterations", registration.max_iterations, "", "Gauss-Newton iterations",
      ge(1));
    v("registration.convergence", registration.convergence, "", "|dx| of convergence", gt(0));
  }
};

/// Registration quality and trust of one scan.
struct OdometryStep {
  bool first = false;  ///< the first scan: it defines the odometry frame, no registration
  bool converged = false;
  int iterations = 0;
  int correspondences = 0;
  double inlier_share = 0.0;
  double rmse = 0.0;                 ///< m
  double threshold = 0.0;            ///< m, correspondence threshold of the first pass (3 sigma)
  bool keyframe = false;             ///< the sweep entered the local map
  std::size_t points = 0;            ///< registered points (after downsampling)
  std::size_t road_user_points = 0;  ///< map-resolution points left out as road users
  StepAssessment assessment;         ///< motion figures and the trust verdict
  bool trusted() const { return first || assessment.trusted; }
};

class ScanOdometry {
 public:
  explicit ScanOdometry(const OdometrySettings& settings);

  /// @brief Registers the next sweep (Velodyne frame).
  /// @param dt time since the previous sweep, s (ignored for the first)
  /// @param exclude optional, one per point: non-zero leaves the point out (e.g. the vehicle
  /// class of a segmentation)
  /// @return the step; its pose is poses().back(), T_odom_velo of the sweep's middle (odom = the
  /// first sweep's Velodyne frame). An untrusted step gets the constant-velocity prediction from
  /// the last trusted sweep, its sweep does not enter the local map and the velocity is kept.
  const OdometryStep& add(const std::vector<Eigen::Vector3f>& scan, double dt,
                          const std::vector<uint8_t>* exclude = nullptr);

  const std::vector<Pose3>& poses() const { return poses_; }
  const std::vector<OdometryStep>& steps() const { return steps_; }
  const LocalVoxelMap& localMap() const { return map_; }

 private:
  double sigma() const;
  void insertKeyframe(const std::vector<Eigen::Vector3d>& frame, const Pose3& T);
  OdometrySettings s_;
  LocalVoxelMap map_;
  std::vector<Pose3> poses_;
  std::vector<OdometryStep> steps_;
  Pose3 trusted_pose_ = Pose3::Identity();    ///< pose of the last trusted sweep
  double since_trusted_ = 0.0;                ///< s since that sweep
  Pose3 last_delta_ = Pose3::Identity();      ///< motion between the last two trusted sweeps
  double last_dt_ = 0.0;                      ///< s, its duration; 0 = velocity unknown
  Pose3 keyframe_ = Pose3::Identity();        ///< pose of the last sweep that entered the map
  std::vector<Eigen::Vector3d> first_frame_;  ///< the first sweep, until it can be de-skewed
  double model_sse_ = 0.0;                    ///< adaptive threshold state (kiss-icp)
  int model_samples_ = 0;
};

/// @brief kiss-icp's KITTI convention for the relative time of a point within its sweep:
/// s = 0.5 * (-atan2(y, x) / pi + 1) in [0, 1], 0.5 = looking forward.
double sweepFraction(const Eigen::Vector3f& p);

/// @brief Constant-velocity de-skew: p' = exp((s - 0.5) * log(motion)) p, with `motion`
/// T_start_end of one sweep; the result is in the frame of the sweep's middle.
std::vector<Eigen::Vector3d> deskewScan(const std::vector<Eigen::Vector3f>& scan,
                                        const Pose3& motion);

/// @brief The rotation of T projected back onto SO(3) (nearest rotation by quaternion
/// normalisation), translation kept.
Pose3 orthonormalized(const Pose3& T);

/// @brief exp(alpha * log(T)): the same constant-velocity motion over alpha times the time.
Pose3 scaleMotion(const Pose3& T, double alpha);

}  // namespace mapfuse::lidar
