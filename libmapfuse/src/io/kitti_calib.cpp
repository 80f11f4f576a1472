#include "mapfuse/io/kitti_calib.hpp"

#include <cmath>
#include <sstream>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/bounds.hpp"

namespace mapfuse::io {
namespace fs = std::filesystem;

namespace {
/// Any number of a calibration file (focal lengths and principal points in px, P_rect_02's
/// baseline term in px m, rotations, translations in m).
constexpr double kMaxCalibNumber = 1e7;
}  // namespace

KittiCalibFile KittiCalibFile::read(const fs::path& path) {
  if (!fs::exists(path)) throw IoError(path.string(), "calibration file not found");
  return parse(readBytes(path), path.string());
}

KittiCalibFile KittiCalibFile::parse(const std::string& text, const std::string& file) {
  KittiCalibFile f;
  f.file_ = file;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const auto colon = line.find(':');
    if (colon == std::string::npos) continue;  // blank or comment lines
    std::string key = line.substr(0, colon);
    while (!key.empty() && std::isspace(static_cast<unsigned char>(key.back()))) key.pop_back();
    std::istringstream ss(line.substr(colon + 1));
    std::vector<std::string> tokens;
    std::string t;
    while (ss >> t) tokens.push_back(t);
    f.values_[key] = tokens;
  }
  return f;
}

std::vector<double> KittiCalibFile::numbers(const std::string& key, std::size_t count) const {
  const auto it = values_.find(key);
  if (it == values_.end()) throw ParseError(file_, key, "missing");
  if (it->second.size() != count)
    throw ParseError(
        file_, key,
        "has " + std::to_string(it->second.size()) + " values, expected " + std::to_string(count));
  std::vector<double> out;
  out.reserve(count);
  for (const std::string& tok : it->second) {
    double x = 0;
    try {
      std::size_t used = 0;
      x = std::stod(tok, &used);
      if (used != tok.size()) throw std::invalid_argument(tok);
    } catch (const std::exception&) {
      throw ParseError(file_, key, "not a number: '" + tok + "'");
    }
    if (!std::isfinite(x)) throw ParseError(file_, key, "not finite: '" + tok + "'");
    if (std::abs(x) > kMaxCalibNumber)
      throw ParseError(
          file_, key,
          "'" + tok + "' is outside " + bounds::rangeText(-kMaxCalibNumber, kMaxCalibNumber));
    out.push_back(x);
  }
  return out;
}

Eigen::MatrixXd KittiCalibFile::matrix(const std::string& key, int rows, int cols) const {
  const auto v = numbers(key, static_cast<std::size_t>(rows * cols));
  Eigen::MatrixXd m(rows, cols);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) m(r, c) = v[static_cast<std::size_t>(r * cols + c)];
  return m;
}

namespace {
Pose3 makeRigid(const Eigen::Matrix3d& R, const Eigen::Vector3d& t, const std::string& file,
                const std::string& key, const std::string& t_key) {
  if (t.cwiseAbs().maxCoeff() > bounds::kMaxExtrinsic)
    throw ParseError(file, t_key,
                     "translation outside " +
                         bounds::rangeText(-bounds::kMaxExtrinsic, bounds::kMaxExtrinsic) + " m");
  if ((R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-3 ||
      R.determinant() < 0)
    throw ParseError(file, key, "is not a rotation matrix");
  Pose3 T = Pose3::Identity();
  // Re-orthonormalise (files carry 7 digits).
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
  T.linear() = svd.matrixU() * svd.matrixV().transpose();
  T.translation() = t;
  return T;
}
}  // namespace

Pose3 KittiCalibFile::rigid(const std::string& r_key, const std::string& t_key) const {
  const Eigen::Matrix3d R = matrix(r_key, 3, 3);
  const Eigen::Vector3d t = matrix(t_key, 3, 1);
  return makeRigid(R, t, file_, r_key, t_key);
}

Pose3 KittiCalibFile::rigid34(const std::string& key) const {
  const Eigen::MatrixXd m = matrix(key, 3, 4);
  return makeRigid(m.block<3, 3>(0, 0), m.col(3), file_, key, key);
}

Eigen::Matrix<double, 3, 4> KittiCalibration::veloToImage2() const {
  return P_rect_02 * T_rect0_velo().matrix();
}

Pose3 KittiCalibration::T_rect0_velo() const {
  Pose3 R = Pose3::Identity();
  R.linear() = R_rect_00;
  return R * T_cam0_velo;
}

KittiCalibration kittiCalibrationFromFiles(const KittiCalibFile& cam, const KittiCalibFile& velo,
                                           const KittiCalibFile* imu) {
  KittiCalibration c;
  c.P_rect_02 = cam.matrix("P_rect_02", 3, 4);
  c.R_rect_00 = cam.matrix("R_rect_00", 3, 3);
  const auto size = cam.numbers("S_rect_02", 2);
  for (double side : size)
    if (!(side >= 1 && side <= double(bounds::kMaxImageSide)))
      throw ParseError(cam.file(), "S_rect_02",
                       "image side " + bounds::numberText(side) + " px is outside [1, " +
                           std::to_string(bounds::kMaxImageSide) + "]");
  c.image_width = static_cast<int>(std::lround(size[0]));
  c.image_height = static_cast<int>(std::lround(size[1]));
  if (*bounds::checkedMultiply(c.image_width, c.image_height) > bounds::kMaxImagePixels)
    throw ParseError(cam.file(), "S_rect_02",
                     "image of " + std::to_string(c.image_width) + "x" +
                         std::to_string(c.image_height) + " px has more than " +
                         std::to_string(bounds::kMaxImagePixels) + " pixels");
  if (!(c.P_rect_02(0, 0) > 0 && c.P_rect_02(1, 1) > 0 && c.P_rect_02(2, 2) == 1.0 &&
        c.P_rect_02(2, 0) == 0 && c.P_rect_02(2, 1) == 0 && c.P_rect_02(1, 0) == 0))
    throw ParseError(cam.file(), "P_rect_02",
                     "not a rectified projection (positive focal lengths, last row 0 0 1 t)");
  const Eigen::Matrix3d& R = c.R_rect_00;
  if ((R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-3 ||
      R.determinant() < 0)
    throw ParseError(cam.file(), "R_rect_00", "is not a rotation matrix");
  c.T_cam0_velo = velo.rigid("R", "T");
  if (imu) {
    c.T_velo_imu = imu->rigid("R", "T");
    c.has_imu = true;
  } else {
    c.T_velo_imu = Pose3::Identity();
  }
  return c;
}

KittiCalibration readKittiCalibration(const fs::path& date_dir) {
  const KittiCalibFile cam = KittiCalibFile::read(date_dir / "calib_cam_to_cam.txt");
  const KittiCalibFile velo = KittiCalibFile::read(date_dir / "calib_velo_to_cam.txt");
  const fs::path imu_path = date_dir / "calib_imu_to_velo.txt";
  if (!fs::exists(imu_path)) return kittiCalibrationFromFiles(cam, velo, nullptr);
  const KittiCalibFile imu = KittiCalibFile::read(imu_path);
  return kittiCalibrationFromFiles(cam, velo, &imu);
}

}  // namespace mapfuse::io
