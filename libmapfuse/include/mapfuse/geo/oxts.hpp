#pragma once
/// @file KITTI OXTS (GPS/IMU) records and the devkit's pose convention (Jeong et al. 2018,
/// eq. 1; KITTI devkit convertOxtsToPose / pykitti): Mercator projection scaled by the
/// cosine of the first frame's latitude, R = Rz(yaw) Ry(pitch) Rx(roll), T_w_imu.
#include <array>

#include "mapfuse/core/se3.hpp"
#include "mapfuse/geo/origin.hpp"

namespace mapfuse::geo {

/// The 30 fields of one OXTS line, in dataformat.txt order.
struct OxtsRecord {
  double lat, lon, alt;               ///< deg, deg, m
  double roll, pitch, yaw;            ///< rad
  double vn, ve, vf, vl, vu;          ///< m/s
  double ax, ay, az, af, al, au;      ///< m/s^2
  double wx, wy, wz, wf, wl, wu;      ///< rad/s
  double pos_accuracy, vel_accuracy;  ///< m, m/s
  int navstat, numsats, posmode, velmode, orimode;
};

/// Earth radius used by the KITTI devkit (m).
constexpr double kKittiEarthRadius = 6378137.0;

/// @brief Mercator scale of the devkit: cos(lat0 * pi / 180).
double mercatorScale(double lat0_deg);

/// @brief Devkit pose of the IMU in the Mercator world frame: tx = s*lon*pi*R/180,
/// ty = s*R*ln(tan((90+lat)*pi/360)), tz = alt; R = Rz(yaw) Ry(pitch) Rx(roll).
Pose3 oxtsToMercatorPose(const OxtsRecord& r, double scale);

/// @brief Pose of the IMU in the ENU frame of `enu` (GeographicLib), same rotation convention
/// (OXTS yaw is measured from East, counter-clockwise, so the axes agree with ENU).
Pose3 oxtsToEnuPose(const OxtsRecord& r, const EnuConverter& enu);

}  // namespace mapfuse::geo
