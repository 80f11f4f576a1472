#pragma once
/// @file KITTI calibration text files ("key: v1 v2 ..." per line): raw-data
/// calib_cam_to_cam.txt / calib_velo_to_cam.txt / calib_imu_to_velo.txt and the odometry
/// benchmark's calib.txt ("P0: ...", "Tr: ..."). Every accessor names the file and key on error.
#include <Eigen/Core>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "mapfuse/core/se3.hpp"

namespace mapfuse::io {

/// One parsed calibration file: key -> numbers (non-numeric values such as calib_time are kept
/// as text and only fail when read as numbers).
class KittiCalibFile {
 public:
  /// @brief Reads and tokenises `path`. @throws IoError when unreadable.
  static KittiCalibFile read(const std::filesystem::path& path);
  /// @brief Parses text that came from `file` (used for messages).
  static KittiCalibFile parse(const std::string& text, const std::string& file);

  bool has(const std::string& key) const { return values_.count(key) != 0; }
  /// @brief Exactly `count` numbers of `key`, each within [-1e7, 1e7].
  /// @throws ParseError(file, key) when missing, not numeric, not finite, out of range or the
  /// wrong count.
  std::vector<double> numbers(const std::string& key, std::size_t count) const;
  /// @brief A rows x cols matrix stored row-major under `key`.
  Eigen::MatrixXd matrix(const std::string& key, int rows, int cols) const;
  /// @brief A rigid transform from R (9 numbers) and T (3 numbers) keys.
  /// @throws ParseError also when R is not a rotation (|R^T R - I| > 1e-3).
  Pose3 rigid(const std::string& r_key, const std::string& t_key) const;
  /// @brief A rigid transform from one 3x4 row-major [R|t] key (odometry "Tr").
  Pose3 rigid34(const std::string& key) const;
  const std::string& file() const { return file_; }

 private:
  std::string file_;
  std::map<std::string, std::vector<std::string>> values_;
};

/// Calibration of one KITTI raw date folder, everything the LiDAR pipeline needs.
struct KittiCalibration {
  Eigen::Matrix<double, 3, 4> P_rect_02;  ///< rectified projection of camera 2 (px)
  Eigen::Matrix3d R_rect_00;              ///< rectifying rotation of camera 0
  Pose3 T_cam0_velo;                      ///< calib_velo_to_cam: velo -> unrectified cam 0 (m)
  Pose3 T_velo_imu;                       ///< calib_imu_to_velo: imu -> velo (m)
  bool has_imu = false;                   ///< calib_imu_to_velo.txt was present
  int image_width = 0;                    ///< S_rect_02 (px)
  int image_height = 0;                   ///< S_rect_02 (px)

  /// @brief eq. (2)-(3), Jeong et al. 2018: P_rect_02 * R_rect_00 * T_cam0_velo (3x4),
  /// maps homogeneous Velodyne points to homogeneous image_02 pixels.
  Eigen::Matrix<double, 3, 4> veloToImage2() const;
  /// @brief Rectified camera-0 frame from Velodyne: R_rect_00 * T_cam0_velo.
  Pose3 T_rect0_velo() const;
};

/// @brief The calibration from parsed files: P_rect_02, R_rect_00, S_rect_02 of `cam`
/// (S_rect_02 within [1, bounds::kMaxImageSide] per side and bounds::kMaxImagePixels in all;
/// P_rect_02 a rectified projection), R / T of `velo` and of `imu` when not null (translations
/// within bounds::kMaxExtrinsic). @throws ParseError naming file and key.
KittiCalibration kittiCalibrationFromFiles(const KittiCalibFile& cam, const KittiCalibFile& velo,
                                           const KittiCalibFile* imu);

/// @brief Reads calib_cam_to_cam.txt and calib_velo_to_cam.txt (required) and
/// calib_imu_to_velo.txt (optional; has_imu says whether it was found) from a date folder.
/// @throws IoError for a missing required file; ParseError naming file and key.
KittiCalibration readKittiCalibration(const std::filesystem::path& date_dir);

}  // namespace mapfuse::io
