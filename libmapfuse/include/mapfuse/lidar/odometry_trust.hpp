#pragma once
/// @file Whether one LiDAR-odometry step can be trusted (docs/lidar.md, "Odometry"): the
/// registration converged, enough of the scan lies on the local map, the matched surfaces
/// constrain every direction of translation, and the motion is one a road vehicle can make.
#include <string>

#include "mapfuse/core/param.hpp"
#include "mapfuse/core/se3.hpp"
#include "mapfuse/lidar/local_voxel_map.hpp"
#include "mapfuse/lidar/map_registration.hpp"

namespace mapfuse::lidar {

struct TrustSettings {
  double min_inlier_share = 0.5;  ///< share of registered points within the threshold of the map
  /// Smallest eigenvalue of the mean n n^T of the matched surface normals (0 .. 1/3): below it
  /// one direction of translation is unconstrained (a featureless plane, a straight tunnel).
  double min_constraint = 0.02;
  double max_speed = 40.0;                  ///< m/s
  double max_rotation_rate = 90.0;          ///< deg/s
  double max_acceleration = 15.0;           ///< m/s^2, change of velocity against the prediction
  double max_angular_acceleration = 600.0;  ///< deg/s^2, the same for the rotation
  /// m and deg: deviations below this are never implausible (2.5x the largest seen on the
  /// simulated drives, 0.2 m: registration noise, not motion)
  double max_deviation_floor = 0.5;

  static constexpr const char* kName = "TrustSettings";  ///< names the owner in messages
  template <class V>
  void visit(V& v) {
    using namespace param;
    v("min_inlier_share", min_inlier_share, "", "share of registered points on the map", in(0, 1));
    v("min_constraint", min_constraint, "",
      "smallest eigenvalue of the mean n n^T of the matched normals", in(0, 1.0 / 3));
    v("max_speed", max_speed, "m/s", "fastest plausible motion", gt(0));
    v("max_rotation_rate", max_rotation_rate, "deg/s", "fastest plausible turn", gt(0));
    v("max_acceleration", max_acceleration, "m/s^2", "largest change of velocity", gt(0));
    v("max_angular_acceleration", max_angular_acceleration, "deg/s^2",
      "largest change of turn rate", gt(0));
    v("max_deviation_floor", max_deviation_floor, "m, deg",
      "deviations below this are never implausible", ge(0));
  }
};

/// Motion and registration figures of one step, and the verdict.
struct StepAssessment {
  double speed = 0.0;          ///< m/s
  double rotation_rate = 0.0;  ///< deg/s
  double deviation_m = 0.0;    ///< m, registered pose against the constant-velocity prediction
  double deviation_deg = 0.0;  ///< deg
  double constraint = 0.0;     ///< smallest eigenvalue of the mean n n^T (see TrustSettings)
  bool trusted = true;
  std::string reasons;  ///< empty when trusted, else "; "-separated causes with their figures
};

/// @brief Smallest eigenvalue of the mean n n^T over the map surfaces matched by every
/// `stride`-th source point at T (map points without a normal are skipped).
/// @return value in [0, 1/3]; 0 when nothing was matched.
double translationConstraint(const LocalVoxelMap& map, const std::vector<Eigen::Vector3d>& source,
                             const Pose3& T_map_scan, double max_distance, int stride = 4);

/// @brief Judges one step.
/// @param reg the registration result
/// @param T_prev pose of the previous scan
/// @param T_pred constant-velocity prediction, or nullptr before the velocity is known (the
/// deviation is then not judged)
/// @param dt time since the previous scan, s
/// @param constraint from translationConstraint
StepAssessment assessStep(const MapRegistrationResult& reg, const Pose3& T_prev,
                          const Pose3* T_pred, double dt, double constraint,
                          const TrustSettings& settings);

}  // namespace mapfuse::lidar
