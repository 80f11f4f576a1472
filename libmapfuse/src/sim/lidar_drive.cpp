#include "mapfuse/sim/lidar_drive.hpp"

namespace mapfuse::sim {

Pose3 egoImuPose(const Road& road, const EgoDrive& drive, const Pose3& T_imu_velo, double t) {
  const double s = drive.start + drive.speed * t;
  const Eigen::Vector2d xy = road.pointAt(s, drive.lateral);
  Pose3 T = poseFromXyzRpy(xy.x(), xy.y(), 0.0, 0.0, 0.0, road.headingAt(s));
  // Raise the IMU so that the Velodyne origin is at velo_height.
  const double velo_z = (T * T_imu_velo).translation().z();
  T.translation().z() = drive.velo_height - velo_z;
  return T;
}

}  // namespace mapfuse::sim
