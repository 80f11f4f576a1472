#include "mapfuse/vehicle/ego_motion.hpp"

#include <algorithm>

namespace mapfuse::vehicle {

std::vector<Pose3> bodyPosesFromPosesFile(std::vector<Pose3> T_world_cam0, const CameraCalib& calib,
                                          bool velo) {
  if (velo) {
    // LiDAR odometry poses (lidar-semantic-map poses.txt) are T_world_velo:
    // T_world_cam0 = T_world_velo * T_cam0_velo^-1 with T_cam0_velo = R_rect_00 T_velo_to_cam.
    const Pose3 T_velo_cam0 = calib.T_posecam_velo.inverse();
    for (Pose3& T : T_world_cam0) T = T * T_velo_cam0;
  }
  // KITTI poses are of (rectified) camera 0; ours is camera 2 shifted by the baseline.
  const Pose3 T_cam0_cam = calib.T_cam_posecam.inverse();
  const Pose3 T_cam_body = calib.T_body_cam.inverse();
  const Pose3 T_first = (T_world_cam0.front() * T_cam0_cam * T_cam_body).inverse();
  std::vector<Pose3> T_odom_body;
  for (const auto& T : T_world_cam0) T_odom_body.push_back(T_first * T * T_cam0_cam * T_cam_body);
  return T_odom_body;
}

OxtsEgoMotion egoMotionFromOxts(const std::vector<geo::OxtsRecord>& rec,
                                const std::vector<double>& stamps) {
  OxtsEgoMotion out;
  const double scale = geo::mercatorScale(rec.front().lat);
  const Pose3 T0_inv = geo::oxtsToMercatorPose(rec.front(), scale).inverse();
  for (const auto& r : rec) out.T_odom_body.push_back(T0_inv * geo::oxtsToMercatorPose(r, scale));
  for (std::size_t i = 0; i < rec.size(); ++i) {
    GpsFix g;
    g.stamp = stamps[i];
    g.position = {rec[i].lat, rec[i].lon, rec[i].alt};
    g.sigma_h = std::max(0.1, rec[i].pos_accuracy);
    g.sigma_v = 2.0 * g.sigma_h;
    out.gps.push_back(g);
  }
  return out;
}

}  // namespace mapfuse::vehicle
