#include "mapfuse/io/kitti_raw_writer.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/png_frames.hpp"

namespace mapfuse::io {
namespace {
// The real KITTI 2011_09_26 calibration files (key layout and values), see ../shared/data.
const char* const kCamToCam = R"KITTI(calib_time: 09-Jan-2012 13:57:47
corner_dist: 9.950000e-02
S_00: 1.392000e+03 5.120000e+02
K_00: 9.842439e+02 0.000000e+00 6.900000e+02 0.000000e+00 9.808141e+02 2.331966e+02 0.000000e+00 0.000000e+00 1.000000e+00
D_00: -3.728755e-01 2.037299e-01 2.219027e-03 1.383707e-03 -7.233722e-02
R_00: 1.000000e+00 0.000000e+00 0.000000e+00 0.000000e+00 1.000000e+00 0.000000e+00 0.000000e+00 0.000000e+00 1.000000e+00
T_00: 2.573699e-16 -1.059758e-16 1.614870e-16
S_rect_00: 1.242000e+03 3.750000e+02
R_rect_00: 9.999239e-01 9.837760e-03 -7.445048e-03 -9.869795e-03 9.999421e-01 -4.278459e-03 7.402527e-03 4.351614e-03 9.999631e-01
P_rect_00: 7.215377e+02 0.000000e+00 6.095593e+02 0.000000e+00 0.000000e+00 7.215377e+02 1.728540e+02 0.000000e+00 0.000000e+00 0.000000e+00 1.000000e+00 0.000000e+00
S_01: 1.392000e+03 5.120000e+02
K_01: 9.895267e+02 0.000000e+00 7.020000e+02 0.000000e+00 9.878386e+02 2.455590e+02 0.000000e+00 0.000000e+00 1.000000e+00
D_01: -3.644661e-01 1.790019e-01 1.148107e-03 -6.298563e-04 -5.314062e-02
R_01: 9.993513e-01 1.860866e-02 -3.083487e-02 -1.887662e-02 9.997863e-01 -8.421873e-03 3.067156e-02 8.998467e-03 9.994890e-01
T_01: -5.370000e-01 4.822061e-03 -1.252488e-02
S_rect_01: 1.242000e+03 3.750000e+02
R_rect_01: 9.996878e-01 -8.976826e-03 2.331651e-02 8.876121e-03 9.999508e-01 4.418952e-03 -2.335503e-02 -4.210612e-03 9.997184e-01
P_rect_01: 7.215377e+02 0.000000e+00 6.095593e+02 -3.875744e+02 0.000000e+00 7.215377e+02 1.728540e+02 0.000000e+00 0.000000e+00 0.000000e+00 1.000000e+00 0.000000e+00
S_02: 1.392000e+03 5.120000e+02
K_02: 9.597910e+02 0.000000e+00 6.960217e+02 0.000000e+00 9.569251e+02 2.241806e+02 0.000000e+00 0.000000e+00 1.000000e+00
D_02: -3.691481e-01 1.968681e-01 1.353473e-03 5.677587e-04 -6.770705e-02
R_02: 9.999758e-01 -5.267463e-03 -4.552439e-03 5.251945e-03 9.999804e-01 -3.413835e-03 4.570332e-03 3.389843e-03 9.999838e-01
T_02: 5.956621e-02 2.900141e-04 2.577209e-03
S_rect_02: 1.242000e+03 3.750000e+02
R_rect_02: 9.998817e-01 1.511453e-02 -2.841595e-03 -1.511724e-02 9.998853e-01 -9.338510e-04 2.827154e-03 9.766976e-04 9.999955e-01
P_rect_02: 7.215377e+02 0.000000e+00 6.095593e+02 4.485728e+01 0.000000e+00 7.215377e+02 1.728540e+02 2.163791e-01 0.000000e+00 0.000000e+00 1.000000e+00 2.745884e-03
S_03: 1.392000e+03 5.120000e+02
K_03: 9.037596e+02 0.000000e+00 6.957519e+02 0.000000e+00 9.019653e+02 2.242509e+02 0.000000e+00 0.000000e+00 1.000000e+00
D_03: -3.639558e-01 1.788651e-01 6.029694e-04 -3.922424e-04 -5.382460e-02
R_03: 9.995599e-01 1.699522e-02 -2.431313e-02 -1.704422e-02 9.998531e-01 -1.809756e-03 2.427880e-02 2.223358e-03 9.997028e-01
T_03: -4.731050e-01 5.551470e-03 -5.250882e-03
S_rect_03: 1.242000e+03 3.750000e+02
R_rect_03: 9.998321e-01 -7.193136e-03 1.685599e-02 7.232804e-03 9.999712e-01 -2.293585e-03 -1.683901e-02 2.415116e-03 9.998553e-01
P_rect_03: 7.215377e+02 0.000000e+00 6.095593e+02 -3.395242e+02 0.000000e+00 7.215377e+02 1.728540e+02 2.199936e+00 0.000000e+00 0.000000e+00 1.000000e+00 2.729905e-03
)KITTI";
const char* const kVeloToCam = R"KITTI(calib_time: 15-Mar-2012 11:37:16
R: 7.533745e-03 -9.999714e-01 -6.166020e-04 1.480249e-02 7.280733e-04 -9.998902e-01 9.998621e-01 7.523790e-03 1.480755e-02
T: -4.069766e-03 -7.631618e-02 -2.717806e-01
delta_f: 0.000000e+00 0.000000e+00
delta_c: 0.000000e+00 0.000000e+00
)KITTI";
const char* const kImuToVelo = R"KITTI(calib_time: 25-May-2012 16:47:16
R: 9.999976e-01 7.553071e-04 -2.035826e-03 -7.854027e-04 9.998898e-01 -1.482298e-02 2.024406e-03 1.482454e-02 9.998881e-01
T: -8.086759e-01 3.195559e-01 -7.997231e-01
)KITTI";
const char* const kDataformat = R"KITTI(lat:   latitude of the oxts-unit (deg)
lon:   longitude of the oxts-unit (deg)
alt:   altitude of the oxts-unit (m)
roll:  roll angle (rad),    0 = level, positive = left side up,      range: -pi   .. +pi
pitch: pitch angle (rad),   0 = level, positive = front down,        range: -pi/2 .. +pi/2
yaw:   heading (rad),       0 = east,  positive = counter clockwise, range: -pi   .. +pi
vn:    velocity towards north (m/s)
ve:    velocity towards east (m/s)
vf:    forward velocity, i.e. parallel to earth-surface (m/s)
vl:    leftward velocity, i.e. parallel to earth-surface (m/s)
vu:    upward velocity, i.e. perpendicular to earth-surface (m/s)
ax:    acceleration in x, i.e. in direction of vehicle front (m/s^2)
ay:    acceleration in y, i.e. in direction of vehicle left (m/s^2)
ay:    acceleration in z, i.e. in direction of vehicle top (m/s^2)
af:    forward acceleration (m/s^2)
al:    leftward acceleration (m/s^2)
au:    upward acceleration (m/s^2)
wx:    angular rate around x (rad/s)
wy:    angular rate around y (rad/s)
wz:    angular rate around z (rad/s)
wf:    angular rate around forward axis (rad/s)
wl:    angular rate around leftward axis (rad/s)
wu:    angular rate around upward axis (rad/s)
pos_accuracy:  velocity accuracy (north/east in m)
vel_accuracy:  velocity accuracy (north/east in m/s)
navstat:       navigation status (see navstat_to_string)
numsats:       number of satellites tracked by primary GPS receiver
posmode:       position mode of primary GPS receiver (see gps_mode_to_string)
velmode:       velocity mode of primary GPS receiver (see gps_mode_to_string)
orimode:       orientation mode of primary GPS receiver (see gps_mode_to_string)
)KITTI";
}  // namespace

std::filesystem::path kittiDriveDir(const std::filesystem::path& root, const std::string& date,
                                    const std::string& name) {
  return root / date / (date + "_drive_" + name + "_sync");
}

std::string kittiFrameName(int index) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%010d", index);
  return buf;
}

void writeKittiCalibration(const std::filesystem::path& date_dir) {
  writeBytesAtomic(date_dir / "calib_cam_to_cam.txt", kCamToCam);
  writeBytesAtomic(date_dir / "calib_velo_to_cam.txt", kVeloToCam);
  writeBytesAtomic(date_dir / "calib_imu_to_velo.txt", kImuToVelo);
}

KittiCalibration writtenKittiCalibration() {
  const KittiCalibFile imu = KittiCalibFile::parse(kImuToVelo, "calib_imu_to_velo.txt");
  return kittiCalibrationFromFiles(KittiCalibFile::parse(kCamToCam, "calib_cam_to_cam.txt"),
                                   KittiCalibFile::parse(kVeloToCam, "calib_velo_to_cam.txt"),
                                   &imu);
}

std::string formatOxtsLine(const geo::OxtsRecord& r) {
  const double d[25] = {r.lat, r.lon, r.alt,          r.roll,        r.pitch, r.yaw, r.vn,
                        r.ve,  r.vf,  r.vl,           r.vu,          r.ax,    r.ay,  r.az,
                        r.af,  r.al,  r.au,           r.wx,          r.wy,    r.wz,  r.wf,
                        r.wl,  r.wu,  r.pos_accuracy, r.vel_accuracy};
  std::string out;
  char buf[40];
  for (double v : d) {
    std::snprintf(buf, sizeof(buf), "%.17g ", v);
    out += buf;
  }
  std::snprintf(buf, sizeof(buf), "%d %d %d %d %d", r.navstat, r.numsats, r.posmode, r.velmode,
                r.orimode);
  return out + buf;
}

void writeOxtsDataformat(const std::filesystem::path& path) {
  writeBytesAtomic(path, kDataformat);
}

std::string formatKittiTimestamp(const std::string& date, double seconds) {
  if (date.size() != 10) throw InputError("KITTI date must look like 2011_09_26: '" + date + "'");
  const auto ns_total = static_cast<long long>(std::llround(seconds * 1e9));
  const long long s = ns_total / 1000000000LL, ns = ns_total % 1000000000LL;
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%s-%s-%s %02lld:%02lld:%02lld.%09lld", date.substr(0, 4).c_str(),
                date.substr(5, 2).c_str(), date.substr(8, 2).c_str(), (s / 3600) % 24,
                (s / 60) % 60, s % 60, ns);
  return buf;
}

void writeLines(const std::filesystem::path& path, const std::vector<std::string>& lines) {
  std::string text;
  for (const auto& l : lines) text += l + "\n";
  writeBytesAtomic(path, text);
}

void writePngBgr(const std::filesystem::path& path, int width, int height,
                 const std::vector<uint8_t>& bgr) {
  if (width <= 0 || height <= 0 || bgr.size() != static_cast<std::size_t>(width) * height * 3)
    throw InputError(path.string() + ": image size does not match its pixels");
  const cv::Mat img(height, width, CV_8UC3, const_cast<uint8_t*>(bgr.data()));
  writePngFrame(path, img);
}

geo::OxtsRecord oxtsFromPose(const Pose3& T_world_imu, const MercatorAnchor& a) {
  geo::OxtsRecord r{};
  const double scale = geo::mercatorScale(a.lat0);
  const double R = geo::kKittiEarthRadius;
  const Eigen::Vector3d d = T_world_imu.translation() - a.world_origin;
  if (d.head<2>().isZero(0.0)) {
    r.lat = a.lat0;
    r.lon = a.lon0;
  } else {
    // Devkit: tx = s*lon*pi*R/180, ty = s*R*ln(tan((90+lat)*pi/360)); solve for lat, lon.
    const double mx = scale * a.lon0 * M_PI * R / 180.0 + d.x();
    const double my = scale * R * std::log(std::tan((90.0 + a.lat0) * M_PI / 360.0)) + d.y();
    r.lon = mx * 180.0 / (scale * M_PI * R);
    r.lat = 360.0 / M_PI * std::atan(std::exp(my / (scale * R))) - 90.0;
  }
  r.alt = a.alt0 + d.z();
  const Eigen::Vector3d rpy = rpyFromRotation(T_world_imu.linear());
  r.roll = rpy.x();
  r.pitch = rpy.y();
  r.yaw = rpy.z();
  r.pos_accuracy = 0.05;
  r.vel_accuracy = 0.02;
  r.navstat = 4;
  r.numsats = 10;
  r.posmode = 4;
  r.velmode = 4;
  r.orimode = 0;
  return r;
}

}  // namespace mapfuse::io
