#pragma once
/// @file Velodyne poses of a KITTI raw drive from OXTS (Jeong et al. 2018, eq. 1), from a
/// KITTI-odometry poses file or from LiDAR odometry, and the choice between them.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "mapfuse/core/param.hpp"
#include "mapfuse/core/se3.hpp"
#include "mapfuse/geo/oxts.hpp"
#include "mapfuse/io/kitti_raw.hpp"
#include "mapfuse/lidar/drive_odometry.hpp"

namespace mapfuse::lidar {

/// Where the poses of a drive come from (docs/lidar.md, "Poses").
struct DrivePoseSettings {
  std::string source = "auto";  ///< auto | oxts | oxts_enu | poses_file | odometry
  std::string poses_file;       ///< KITTI poses file, T_world_cam0 (docs/kitti.md, "Poses files")
  DriveOdometrySettings odometry;

  template <class V>
  void visit(V& v) {
    v("pose_source", source, "",
      "auto|oxts|oxts_enu|poses_file|odometry (auto: OXTS when every frame has it, else the poses "
      "file if given or the sequence's poses.txt, else odometry)",
      param::oneOf({"auto", "oxts", "oxts_enu", "poses_file", "odometry"}));
    v("poses_file", poses_file, "",
      "KITTI poses file, T_world_cam0 (line i = frame i, or one line per selected frame; "
      "docs/kitti.md)");
    odometry.visit(v);
  }
};

/// The poses of the selected frames and where they came from.
struct DrivePoses {
  std::vector<Pose3> T_map_velo;  ///< one per selected frame; the first at the origin
  std::string source;             ///< oxts | oxts_enu | poses_file | odometry (auto resolved)
  Eigen::Vector3d origin_translation = Eigen::Vector3d::Zero();  ///< m, OXTS: removed by recenter
  std::optional<geo::OxtsRecord> origin_fix;    ///< OXTS: the first selected frame's fix
  std::filesystem::path file;                   ///< poses_file: the file read
  std::optional<DriveOdometryResult> odometry;  ///< odometry: steps and trust
};

/// @brief Poses of the selected frames in the map frame (first selected frame at the origin).
/// `auto` takes OXTS when every frame has it (and the calibration has IMU), else the poses file
/// (settings or the sequence's poses.txt) when there is one, else LiDAR odometry.
/// @throws InputError when OXTS is asked for but missing, or odometry is not trusted (see
/// runDriveOdometry); ConfigError when poses_file is asked for but none is known.
DrivePoses drivePoses(const io::KittiRawDrive& drive, const DrivePoseSettings& settings);

/// @brief T_w_velo = T_w_imu * inv(T_velo_imu) for every selected frame, with T_w_imu the
/// KITTI devkit pose (Mercator scaled by cos(lat of the first selected frame)) or, with
/// `enu`, the ENU pose about the first frame's fix (GeographicLib).
/// @throws IoError / ParseError when an OXTS record is missing or malformed; InputError when
/// the calibration has no calib_imu_to_velo.txt.
std::vector<Pose3> oxtsVeloPoses(const io::KittiRawDrive& drive, bool enu);

/// @brief Velodyne poses from camera poses of a KITTI-odometry poses file:
/// T_velo0_velo_i = inv(T_cam_velo) * T_cam0_cam_i * T_cam_velo.
std::vector<Pose3> veloPosesFromCameraPoses(const std::vector<Pose3>& T_cam0_cam,
                                            const Pose3& T_cam_velo);

/// @brief Velodyne poses of the selected frames from a poses file of T_world_cam0 (KITTI
/// convention, io/kitti_poses.hpp), in the map frame of a run from a poses file: the Velodyne
/// frame of the first selected frame. Lines are matched to frames by one of two rules, which
/// agree whenever both apply: line i = frame i when the file has a line for every index up to
/// the last selected frame (a KITTI odometry or SemanticKITTI file); else line k = the k-th
/// selected frame when the file has exactly one line per selected frame (what lidar-semantic-map
/// writes for a --first-frame/--stride selection).
/// @throws InputError naming the file when neither rule applies; IoError / ParseError from the
/// reader (checked before anything else is read).
std::vector<Pose3> veloPosesFromFile(const io::KittiRawDrive& drive,
                                     const std::filesystem::path& poses_file);

/// @brief The KITTI poses file of a run: T_cam0first_cam0_i = T_cam_velo * inv(T_map_velo_0) *
/// T_map_velo_i * inv(T_cam_velo), camera 0 of the first frame as world, whatever the map frame.
std::vector<Pose3> cameraPosesForFile(const std::vector<Pose3>& T_map_velo,
                                      const Pose3& T_cam_velo);

/// @brief Moves the poses so that the first lies at the origin (translation only, axes kept:
/// keeps z up for OXTS worlds). @return the removed translation (m).
Eigen::Vector3d recenter(std::vector<Pose3>& T_w_velo);

/// @brief Where the poses came from, for the summary: source, the origin (translation and WGS84
/// fix), the poses file, and the odometry's report when the poses are LiDAR odometry.
nlohmann::json posesReport(const DrivePoses& poses, const DriveOdometrySettings& odometry);

}  // namespace mapfuse::lidar
