#include "mapfuse/io/camera_calib.hpp"

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/bounds.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/json_geometry.hpp"
#include "mapfuse/io/json_view.hpp"
#include "mapfuse/io/kitti_calib.hpp"

namespace mapfuse::io {
namespace {
/// Focal lengths and principal point (px).
constexpr double kMaxIntrinsic = 1e7;
}  // namespace

CameraCalib readCameraCalib(const std::filesystem::path& path) {
  return cameraCalibFromJson(readDocument(path), path.string());
}

CameraCalib cameraCalibFromJson(const Json& doc, const std::string& file) {
  const JsonView v(doc, file);
  v.checkFormat(kCameraCalibFormat, 1);
  v.onlyKeys({"format", "version", "K", "width", "height", "distortion", "T_body_cam",
              "camera_height", "ground_normal_cam"});
  CameraCalib c;
  const Eigen::VectorXd k = v.at("K").vector(9);
  if (k.cwiseAbs().maxCoeff() > kMaxIntrinsic)
    v.at("K").fail("entries must be within " + bounds::rangeText(-kMaxIntrinsic, kMaxIntrinsic));
  c.K = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(k.data());
  if (!(c.K(0, 0) > 0.0 && c.K(1, 1) > 0.0)) v.at("K").fail("focal lengths must be positive");
  if (c.K(2, 0) != 0.0 || c.K(2, 1) != 0.0 || c.K(2, 2) != 1.0 || c.K(1, 0) != 0.0)
    v.at("K").fail("must be an upper-triangular pinhole matrix with last row [0, 0, 1]");
  c.width = int(v.at("width").integer(1, bounds::kMaxImageSide));
  c.height = int(v.at("height").integer(1, bounds::kMaxImageSide));
  if (int64_t(c.width) * c.height > bounds::kMaxImagePixels)
    v.at("height").fail("image has more than " + std::to_string(bounds::kMaxImagePixels) +
                        " pixels");
  if (auto d = v.find("distortion")) {
    const Eigen::VectorXd dist = d->vector(0);
    if (dist.size() > 0 && dist.cwiseAbs().maxCoeff() > 0.0)
      d->fail("lens distortion is not supported: rectify the images first");
  }
  c.T_body_cam = readPose(v.at("T_body_cam"));
  if (c.T_body_cam.translation().cwiseAbs().maxCoeff() > bounds::kMaxExtrinsic)
    v.at("T_body_cam")
        .at("t")
        .fail("outside " + bounds::rangeText(-bounds::kMaxExtrinsic, bounds::kMaxExtrinsic) + " m");
  c.ground.height = v.at("camera_height").number(0.0, bounds::kMaxExtrinsic);
  if (!(c.ground.height > 0.0)) v.at("camera_height").fail("must be positive");
  const Eigen::Vector3d n = v.at("ground_normal_cam").vec3();
  if (std::abs(n.norm() - 1.0) > 1e-3) v.at("ground_normal_cam").fail("must be a unit vector");
  if (n.y() >= 0.0)
    v.at("ground_normal_cam").fail("must point up (negative y in the camera frame)");
  c.ground.normal_cam = n.normalized();
  return c;
}

CameraCalib readKittiCameraCalib(const std::filesystem::path& date_dir, double camera_height) {
  if (!(camera_height > 0.0))
    throw InputError("KITTI camera height must be positive (got " + std::to_string(camera_height) +
                     ")");
  const KittiCalibration kc = readKittiCalibration(date_dir);
  CameraCalib c;
  c.K = kc.P_rect_02.leftCols<3>();
  c.width = kc.image_width;
  c.height = kc.image_height;
  // Rectified camera 2 is rectified camera 0 shifted by the baseline in P_rect_02.
  Pose3 T_rect2_rect0 = Pose3::Identity();
  T_rect2_rect0.translation() = c.K.inverse() * kc.P_rect_02.col(3);
  c.T_cam_posecam = T_rect2_rect0;
  c.T_posecam_velo = kc.T_rect0_velo();
  c.has_velo = true;
  if (kc.has_imu) {
    const Pose3 T_cam_imu = T_rect2_rect0 * c.T_posecam_velo * kc.T_velo_imu;
    c.T_body_cam = T_cam_imu.inverse();
  } else {
    c.T_body_cam.linear() = levelCameraToBodyRotation();
  }
  c.ground.height = camera_height;
  c.ground.normal_cam = (c.T_body_cam.linear().transpose() * Eigen::Vector3d::UnitZ()).normalized();
  return c;
}

}  // namespace mapfuse::io
