#pragma once
/// @file Ego-motion of a drive from the sources besides dead reckoning (docs/lsm-build.md
/// "Ego-motion"): a KITTI odometry poses file (camera 0, or the Velodyne of
/// lidar-semantic-map's poses.txt) and the OXTS records of a KITTI raw drive.
#include <vector>

#include "mapfuse/core/drive_records.hpp"
#include "mapfuse/core/lsm.hpp"
#include "mapfuse/geo/oxts.hpp"

namespace mapfuse::vehicle {

/// @brief Body poses T_odom_body (odom = the first frame's body) from poses of the poses-file
/// camera (T_world_cam0, KITTI odometry), or of the Velodyne (T_world_velo) when `velo`.
/// @param calib needs has_velo when `velo`.
std::vector<Pose3> bodyPosesFromPosesFile(std::vector<Pose3> T_world_poses,
                                          const CameraCalib& calib, bool velo);

/// Ego-motion and GPS of a KITTI raw drive from its OXTS records.
struct OxtsEgoMotion {
  std::vector<Pose3> T_odom_body;  ///< per record; odom = the first record's body (Mercator)
  std::vector<GpsFix> gps;         ///< one fix per record
};

/// @brief Poses from geo::oxtsToMercatorPose relative to the first record, and one GPS fix per
/// record at `stamps` (sigma_h = max(0.1 m, position accuracy), sigma_v = 2 sigma_h).
OxtsEgoMotion egoMotionFromOxts(const std::vector<geo::OxtsRecord>& records,
                                const std::vector<double>& stamps);

}  // namespace mapfuse::vehicle
