#include "mapfuse/sim/lidar_drive.hpp"

#include <algorithm>
#include <chrono>

namespace mapfuse::sim {
namespace {
double since(std::chrono::steady_clock::time_point a) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count();
}
}  // namespace

Pose3 egoImuPose(const Road& road, const EgoDrive& drive, const Pose3& T_imu_velo, double t) {
  const double s = drive.start + drive.speed * t;
  const Eigen::Vector2d xy = road.pointAt(s, drive.lateral);
  Pose3 T = poseFromXyzRpy(xy.x(), xy.y(), 0.0, 0.0, 0.0, road.headingAt(s));
  // Raise the IMU so that the Velodyne origin is at velo_height.
  const double velo_z = (T * T_imu_velo).translation().z();
  T.translation().z() = drive.velo_height - velo_z;
  return T;
}

LidarDrive::LidarDrive(const LidarDriveSettings& s, const io::KittiCalibration& calib,
                       uint64_t seed)
    : settings_(s),
      calib_(calib),
      seed_(seed),
      scene_(generateStreet(s.street, seed)),
      ego_{s.street.ego_start, s.street.ego_speed, -0.5 * s.street.profile.lane_width,
           s.velo_height},
      T_imu_velo_(calib.T_velo_imu.inverse()) {}

double LidarDrive::endArcLength() const {
  return ego_.start + ego_.speed * (settings_.frames - 1) / settings_.frame_rate;
}

Pose3 LidarDrive::imuPose(double t) const {
  return egoImuPose(scene_.road(), ego_, T_imu_velo_, t);
}

LidarFrame LidarDrive::frame(int k) const {
  LidarFrame f;
  f.time = k / settings_.frame_rate;
  const double dt = 1.0 / settings_.frame_rate;
  f.T_world_imu = imuPose(f.time);
  f.T_world_velo = f.T_world_imu * T_imu_velo_;
  f.T_world_imu_next = imuPose(f.time + dt);
  auto t0 = std::chrono::steady_clock::now();
  f.scan = scanLidar(scene_, f.T_world_velo, f.time, settings_.sensor,
                     hashKey(seed_, static_cast<uint64_t>(k), 1));
  f.seconds_lidar = since(t0);
  t0 = std::chrono::steady_clock::now();
  f.camera = renderLabels(scene_, calib_, f.T_world_velo, f.time, settings_.camera_max_range);
  f.probabilities = networkProbabilities(f.camera, settings_.network,
                                         hashKey(seed_, static_cast<uint64_t>(k), 2));
  f.seconds_camera = since(t0);
  return f;
}

geo::OxtsRecord oxtsRecord(const Pose3& T_world_imu, const Pose3& T_next, double dt,
                           const io::MercatorAnchor& anchor) {
  geo::OxtsRecord rec = io::oxtsFromPose(T_world_imu, anchor);
  const Eigen::Vector3d v_world = (T_next.translation() - T_world_imu.translation()) / dt;
  const Eigen::Vector3d v_body = T_world_imu.linear().transpose() * v_world;
  rec.ve = v_world.x();
  rec.vn = v_world.y();
  rec.vu = v_world.z();
  rec.vf = v_body.x();
  rec.vl = v_body.y();
  rec.az = rec.au = 9.81;
  rec.wz = rec.wu = logSE3(T_world_imu.inverse() * T_next)(5) / dt;
  return rec;
}

void LidarScanStats::add(const LidarScan& scan) {
  total += scan.points.size();
  min = std::min(min, scan.points.size());
  max = std::max(max, scan.points.size());
  for (uint32_t w : scan.labels) {
    const uint16_t id = static_cast<uint16_t>(w & 0xFFFF);
    ++per_class[static_cast<int>(lidarClassFromSemanticKitti(id))];
    moving_vehicle += id == kSemanticKittiMovingCar;
  }
}

}  // namespace mapfuse::sim
