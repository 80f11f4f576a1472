#pragma once
/// @file The ego drive of the LiDAR simulator (docs/lidar-ground-truth.md): the vehicle follows
/// the right lane's centre at constant speed; the IMU pose is T_world_imu (x forward, y left,
/// z up) and the Velodyne pose T_world_velo = T_world_imu * T_imu_velo with the KITTI
/// extrinsics. Per frame: a LiDAR scan, the camera's true labels and network-like
/// probabilities, all seeded by (drive seed, frame), so frames are independent of each other.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "mapfuse/core/param.hpp"
#include "mapfuse/core/se3.hpp"
#include "mapfuse/geo/oxts.hpp"
#include "mapfuse/io/kitti_calib.hpp"
#include "mapfuse/io/kitti_raw_writer.hpp"
#include "mapfuse/sim/lidar_camera.hpp"
#include "mapfuse/sim/lidar_network_error.hpp"
#include "mapfuse/sim/lidar_road.hpp"
#include "mapfuse/sim/lidar_scene.hpp"
#include "mapfuse/sim/lidar_scene_generator.hpp"
#include "mapfuse/sim/lidar_sensor.hpp"

namespace mapfuse::sim {

struct EgoDrive {
  double start = 25.0;        ///< m, arc length at t = 0
  double speed = 8.0;         ///< m/s
  double lateral = -1.75;     ///< m, lane centre (right lane: negative)
  double velo_height = 1.73;  ///< m, Velodyne above the road
};

/// @brief T_world_imu at time t (s) such that the Velodyne sits velo_height above the road.
Pose3 egoImuPose(const Road& road, const EgoDrive& drive, const Pose3& T_imu_velo, double t);

/// Parameters of the synthetic drive; each declared once, in the visit() of the struct that
/// owns it.
struct LidarDriveSettings {
  int frames = 60;                 ///< number of frames
  double frame_rate = 10.0;        ///< Hz
  double velo_height = 1.73;       ///< m, Velodyne above the road
  double camera_max_range = 80.0;  ///< m, farther surfaces render as sky
  StreetParams street;             ///< the scene (and the ego's start and speed)
  LidarSensorParams sensor;
  NetworkErrorParams network;

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("frames", frames, "", "number of frames", in(1, 100000));
    v("frame_rate", frame_rate, "Hz", "sensor rate", gt(0) & le(1000));
    street.visit(v);
    v("velo_height", velo_height, "m", "Velodyne height above the road", gt(0) & le(100));
    v.relation("curb_height", street.profile.curb_height, street.profile.curb_height < velo_height,
               "< velo_height");
    sensor.visit(v);
    v("camera_max_range", camera_max_range, "m", "farther surfaces render as sky",
      gt(0) & le(10000));
    network.visit(v);
  }
};

/// What the sensors record in one frame.
struct LidarFrame {
  double time = 0.0;  ///< s after frame 0
  Pose3 T_world_imu = Pose3::Identity();
  Pose3 T_world_velo = Pose3::Identity();
  Pose3 T_world_imu_next = Pose3::Identity();        ///< one frame later (OXTS velocities)
  LidarScan scan;                                    ///< Velodyne frame, true labels
  CameraFrame camera;                                ///< true label image of image_02
  io::SemanticImage probabilities;                   ///< network-like, from the true labels
  double seconds_lidar = 0.0, seconds_camera = 0.0;  ///< s, scan; render and network
};

/// The synthetic drive: its street, generated from the seed, and any frame on demand.
class LidarDrive {
 public:
  /// @param calib the KITTI calibration the drive is written with (Velodyne, IMU, camera 2)
  /// @param seed seeds the street and every noise draw
  LidarDrive(const LidarDriveSettings& settings, const io::KittiCalibration& calib, uint64_t seed);

  const LidarScene& scene() const { return scene_; }
  /// @brief m, arc length of the last frame's IMU on the road.
  double endArcLength() const;
  /// @brief T_world_imu at time t (s after frame 0).
  Pose3 imuPose(double t) const;
  /// @brief Frame k at t = k / frame_rate: poses, scan, camera labels, probabilities.
  LidarFrame frame(int k) const;

 private:
  LidarDriveSettings settings_;
  const io::KittiCalibration& calib_;
  uint64_t seed_;
  LidarScene scene_;
  EgoDrive ego_;
  Pose3 T_imu_velo_;
};

/// @brief The OXTS record of a frame: position and attitude of T_world_imu (io::oxtsFromPose),
/// velocities and yaw rate from the pose `dt` s later, gravity as acceleration.
geo::OxtsRecord oxtsRecord(const Pose3& T_world_imu, const Pose3& T_world_imu_next, double dt,
                           const io::MercatorAnchor& anchor);

/// Point counts of the scans of a drive.
struct LidarScanStats {
  std::size_t total = 0, min = SIZE_MAX, max = 0;
  std::size_t moving_vehicle = 0;  ///< points on moving cars (SemanticKITTI 252)
  std::vector<std::size_t> per_class = std::vector<std::size_t>(kNumLidarClasses, 0);

  /// @brief Counts one scan's points by true class.
  void add(const LidarScan& scan);
};

}  // namespace mapfuse::sim
