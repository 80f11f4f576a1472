#include "mapfuse/lidar/drive_poses.hpp"

#include "mapfuse/core/error.hpp"
#include "mapfuse/geo/origin.hpp"
#include "mapfuse/geo/oxts.hpp"

namespace mapfuse::lidar {

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

Eigen::Vector3d recenter(std::vector<Pose3>& T_w_velo) {
  if (T_w_velo.empty()) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d t0 = T_w_velo[0].translation();
  for (Pose3& T : T_w_velo) T.translation() -= t0;
  return t0;
}

}  // namespace mapfuse::lidar
