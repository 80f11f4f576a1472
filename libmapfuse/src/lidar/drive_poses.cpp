#include "mapfuse/lidar/drive_poses.hpp"

#include "mapfuse/core/error.hpp"
#include "mapfuse/geo/origin.hpp"
#include "mapfuse/geo/oxts.hpp"
#include "mapfuse/io/kitti_poses.hpp"
#include "mapfuse/lidar/scan_odometry.hpp"

namespace mapfuse::lidar {
namespace fs = std::filesystem;

std::vector<Pose3> oxtsVeloPoses(const io::KittiRawDrive& drive, bool enu) {
  if (!drive.calib.has_imu)
    throw InputError(drive.date_dir.string() + ": calib_imu_to_velo.txt is needed for OXTS poses");
  std::vector<geo::OxtsRecord> rec;
  rec.reserve(drive.frames.size());
  for (const auto& f : drive.frames) rec.push_back(io::readOxts(f));
  const Pose3 T_imu_velo = drive.calib.T_velo_imu.inverse();
  std::vector<Pose3> out;
  out.reserve(rec.size());
  if (enu) {
    const geo::EnuConverter conv(geo::GeoOrigin{rec[0].lat, rec[0].lon, rec[0].alt});
    for (const auto& r : rec) out.push_back(geo::oxtsToEnuPose(r, conv) * T_imu_velo);
  } else {
    const double scale = geo::mercatorScale(rec[0].lat);  // eq. (1), devkit convention
    for (const auto& r : rec) out.push_back(geo::oxtsToMercatorPose(r, scale) * T_imu_velo);
  }
  return out;
}

std::vector<Pose3> veloPosesFromCameraPoses(const std::vector<Pose3>& T_cam0_cam,
                                            const Pose3& T_cam_velo) {
  std::vector<Pose3> out;
  out.reserve(T_cam0_cam.size());
  const Pose3 T_velo_cam = T_cam_velo.inverse();
  for (const Pose3& T : T_cam0_cam) out.push_back(T_velo_cam * T * T_cam_velo);
  return out;
}

std::vector<Pose3> veloPosesFromFile(const io::KittiRawDrive& drive,
                                     const std::filesystem::path& poses_file) {
  const std::vector<Pose3> cam = io::readKittiOdometryPoses(poses_file);
  const std::size_t last = static_cast<std::size_t>(drive.frames.back().index);
  std::vector<Pose3> sel;
  if (cam.size() > last) {
    for (const auto& f : drive.frames) sel.push_back(cam[static_cast<std::size_t>(f.index)]);
  } else if (cam.size() == drive.frames.size()) {
    sel = cam;
  } else {
    throw InputError(poses_file.string() + " has " + std::to_string(cam.size()) +
                     " poses: neither one per frame index up to the last selected frame " +
                     std::to_string(last) + " nor one per selected frame (" +
                     std::to_string(drive.frames.size()) + ")");
  }
  // R_rect_00 carries ~7 digits: its product with Tr is projected back onto SE(3), in both
  // directions (cameraPosesForFile), so that a file written and read again is the same.
  std::vector<Pose3> poses =
      veloPosesFromCameraPoses(sel, orthonormalized(drive.calib.T_rect0_velo()));
  const Pose3 T0inv = poses.front().inverse();
  for (Pose3& T : poses) T = T0inv * T;
  return poses;
}

std::vector<Pose3> cameraPosesForFile(const std::vector<Pose3>& T_map_velo,
                                      const Pose3& T_cam_velo) {
  std::vector<Pose3> out;
  if (T_map_velo.empty()) return out;
  const Pose3 T_cv = orthonormalized(T_cam_velo);
  const Pose3 T0inv = T_map_velo.front().inverse(), T_velo_cam = T_cv.inverse();
  for (const Pose3& T : T_map_velo) out.push_back(orthonormalized(T_cv * (T0inv * T) * T_velo_cam));
  return out;
}

Eigen::Vector3d recenter(std::vector<Pose3>& T_w_velo) {
  if (T_w_velo.empty()) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d t0 = T_w_velo[0].translation();
  for (Pose3& T : T_w_velo) T.translation() -= t0;
  return t0;
}

DrivePoses drivePoses(const io::KittiRawDrive& drive, const DrivePoseSettings& s) {
  DrivePoses out;
  out.source = s.source;
  if (out.source == "auto")
    out.source = (drive.has_oxts && drive.calib.has_imu)              ? "oxts"
                 : !s.poses_file.empty() || !drive.poses_file.empty() ? "poses_file"
                                                                      : "odometry";
  if (out.source == "oxts" || out.source == "oxts_enu") {
    if (!drive.has_oxts) throw InputError(drive.dir.string() + ": not every frame has OXTS");
    out.T_map_velo = oxtsVeloPoses(drive, out.source == "oxts_enu");
    out.origin_translation = recenter(out.T_map_velo);
    out.origin_fix = io::readOxts(drive.frames.front());
  } else if (out.source == "poses_file") {
    out.file = !s.poses_file.empty() ? fs::path(s.poses_file) : drive.poses_file;
    if (out.file.empty())
      throw ConfigError("pose_source poses_file needs --poses-file (or a sequence's poses.txt)");
    out.T_map_velo = veloPosesFromFile(drive, out.file);
  } else if (out.source == "odometry") {
    out.odometry = runDriveOdometry(drive, s.odometry);
    out.T_map_velo = out.odometry->T_odom_velo;
  } else {
    throw ConfigError("pose_source = \"" + s.source +
                      "\". Violated constraint: one of auto, oxts, oxts_enu, poses_file, odometry");
  }
  return out;
}

nlohmann::json posesReport(const DrivePoses& p, const DriveOdometrySettings& odometry) {
  nlohmann::json j = {{"source", p.source}};
  if (p.origin_fix) {
    const Eigen::Vector3d& t = p.origin_translation;
    j["origin_translation"] = {t.x(), t.y(), t.z()};
    j["origin_wgs84"] = {
        {"lat", p.origin_fix->lat}, {"lon", p.origin_fix->lon}, {"alt", p.origin_fix->alt}};
  }
  if (!p.file.empty()) j["file"] = p.file.string();
  if (p.odometry) j.update(odometryReport(*p.odometry, odometry));
  return j;
}

}  // namespace mapfuse::lidar
