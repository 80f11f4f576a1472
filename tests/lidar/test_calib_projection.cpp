// OXTS -> devkit pose of drive 0005 frame 0, and the projection of its scan onto image_02.
#include <catch2/catch.hpp>
#include <cmath>

#include "mapfuse/io/kitti_raw.hpp"
#include "mapfuse/io/velodyne.hpp"
#include "mapfuse/lidar/drive_poses.hpp"
#include "mapfuse/lidar/projection.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;

namespace {
constexpr double kPoseTol = 1e-6;      // m: same formula, evaluated independently
constexpr double kMatrixTol = 1e-3;    // calibration R has 7 digits; the library orthonormalises
constexpr double kPixelTol = 1e-3;     // px: hand-composed matrices vs the library
constexpr double kFovMarginDeg = 1.0;  // projected points lie inside the camera's FOV
const char* const kDrive = "data/kitti_raw/2011_09_26/2011_09_26_drive_0005_sync";

Eigen::Matrix3d rz(double a) {
  return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).matrix();
}
Eigen::Matrix3d ry(double a) {
  return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitY()).matrix();
}
Eigen::Matrix3d rx(double a) {
  return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitX()).matrix();
}
}  // namespace

TEST_CASE("OXTS of drive 0005 frame 0 gives the devkit pose", "[lidar][poses]") {
  const auto drive = io::openKittiRawDrive(test::requireShared(kDrive), {});
  const auto ox = io::readOxts(drive.frames[0]);
  // devkit convertOxtsToPose, written out from the data README
  const double er = 6378137.0, scale = std::cos(49.011212804408 * M_PI / 180.0);
  const Eigen::Vector3d t(scale * 8.4228850417969 * M_PI * er / 180.0,
                          scale * er * std::log(std::tan((90.0 + 49.011212804408) * M_PI / 360.0)),
                          112.83492279053);
  Eigen::Matrix4d T_w_imu = Eigen::Matrix4d::Identity();
  T_w_imu.block<3, 3>(0, 0) = rz(ox.yaw) * ry(ox.pitch) * rx(ox.roll);
  T_w_imu.block<3, 1>(0, 3) = t;
  // calib_imu_to_velo.txt R, T typed in from the file
  Eigen::Matrix4d T_velo_imu = Eigen::Matrix4d::Identity();
  T_velo_imu.block<3, 3>(0, 0) << 9.999976e-01, 7.553071e-04, -2.035826e-03, -7.854027e-04,
      9.998898e-01, -1.482298e-02, 2.024406e-03, 1.482454e-02, 9.998881e-01;
  T_velo_imu.block<3, 1>(0, 3) << -8.086759e-01, 3.195559e-01, -7.997231e-01;
  const Eigen::Matrix4d expected = T_w_imu * T_velo_imu.inverse();
  const auto poses = lidar::oxtsVeloPoses(drive, false);
  REQUIRE(poses.size() == 1);
  CHECK((poses[0].matrix() - expected).cwiseAbs().maxCoeff() < kMatrixTol);
  CHECK((poses[0].translation() - expected.block<3, 1>(0, 3)).norm() < kMatrixTol);
  // the IMU position itself is exactly the devkit Mercator point
  const Pose3 T_w_imu_lib = poses[0] * drive.calib.T_velo_imu;
  CHECK((T_w_imu_lib.translation() - t).norm() < kPoseTol);
  // ENU option: origin at the first fix -> IMU at (0, 0, 0)
  const auto enu = lidar::oxtsVeloPoses(drive, true);
  CHECK((enu[0] * drive.calib.T_velo_imu).translation().norm() < kPoseTol);
}

TEST_CASE("drive 0005 frame 0 scan projects onto image_02 as the calibration says",
          "[lidar][projection]") {
  const auto drive = io::openKittiRawDrive(test::requireShared(kDrive), {});
  const auto scan = io::readVelodyneBin(drive.frames[0].velodyne);
  // Hand-composed P_rect_02 * R_rect_00 * [R|T]_velo_to_cam, numbers typed from the files.
  Eigen::Matrix<double, 3, 4> P2;
  P2 << 7.215377e+02, 0, 6.095593e+02, 4.485728e+01, 0, 7.215377e+02, 1.728540e+02, 2.163791e-01, 0,
      0, 1, 2.745884e-03;
  Eigen::Matrix4d Rr = Eigen::Matrix4d::Identity();
  Rr.block<3, 3>(0, 0) << 9.999239e-01, 9.837760e-03, -7.445048e-03, -9.869795e-03, 9.999421e-01,
      -4.278459e-03, 7.402527e-03, 4.351614e-03, 9.999631e-01;
  Eigen::Matrix4d Tv = Eigen::Matrix4d::Identity();
  Tv.block<3, 3>(0, 0) << 7.533745e-03, -9.999714e-01, -6.166020e-04, 1.480249e-02, 7.280733e-04,
      -9.998902e-01, 9.998621e-01, 7.523790e-03, 1.480755e-02;
  Tv.block<3, 1>(0, 3) << -4.069766e-03, -7.631618e-02, -2.717806e-01;
  const Eigen::Matrix<double, 3, 4> M = P2 * Rr * Tv;
  const auto lib = drive.calib.veloToImage2();
  for (const Eigen::Vector3d& p :
       {Eigen::Vector3d(10, 0, 0), Eigen::Vector3d(20, 5, -1.5), Eigen::Vector3d(8, -3, 0.5),
        Eigen::Vector3d(scan.points[1000].cast<double>())}) {
    const Eigen::Vector3d h = M * p.homogeneous();
    double u = 0, v = 0;
    if (!lidar::projectPoint(lib, p, &u, &v)) continue;
    CHECK(std::abs(u - h.x() / h.z()) < kPixelTol);
    CHECK(std::abs(v - h.y() / h.z()) < kPixelTol);
  }
  // A point 10 m straight ahead of the Velodyne lands near the principal point, slightly below
  // (the camera is 8 cm lower and 27 cm behind): u ~ 609.6 + 721.5 * (-0.004 - 0 + ...)/10.
  double u0 = 0, v0 = 0;
  REQUIRE(lidar::projectPoint(lib, {10, 0, 0}, &u0, &v0));
  CHECK(std::abs(u0 - 609.6) < 15);
  CHECK(v0 > 172.9);
  CHECK(v0 < 260);

  const lidar::ProjectionSettings s;
  const lidar::ImageProjection camera{lib, drive.calib.image_width, drive.calib.image_height};
  const auto pr = lidar::projectScan(scan.points, camera, s);
  std::size_t in_range = 0, in_fov = 0;
  const double half_fov = std::atan2(1242.0 / 2.0, 721.5377) * 180.0 / M_PI;  // ~40.7 deg
  for (const auto& p : scan.points) {
    const double r = p.norm();
    if (r < 5 || r > 50) continue;
    ++in_range;
    if (std::abs(std::atan2(p.y(), p.x()) * 180.0 / M_PI) < half_fov - kFovMarginDeg) ++in_fov;
  }
  INFO("projected " << pr.size() << " of " << in_range << " in range; in horizontal FOV "
                    << in_fov);
  // Every projected point is in range and within the horizontal field of view (+ margin).
  std::size_t outside = 0;
  for (std::size_t k = 0; k < pr.size(); ++k) {
    const auto& p = scan.points[pr.point_index[k]];
    outside += std::abs(std::atan2(p.y(), p.x()) * 180.0 / M_PI) >= half_fov + 2 * kFovMarginDeg;
  }
  CHECK(outside == 0);
  // The camera's vertical FOV (+-14.6 deg) covers most of the HDL-64 (+2..-24.8 deg) rays near
  // the horizon; at 5-50 m at least 70 % of the points inside the horizontal FOV project.
  CHECK(pr.size() >= 0.7 * in_fov);
  CHECK(pr.size() <= in_range);
}
