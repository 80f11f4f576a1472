#pragma once
/// @file Writer of KITTI raw drives (the layout the KITTI raw reader and the devkit expect):
/// `<root>/<date>/calib_cam_to_cam.txt, calib_velo_to_cam.txt, calib_imu_to_velo.txt` and
/// `<root>/<date>/<date>_drive_<name>_sync/{image_02/data/*.png, image_02/timestamps.txt,
/// velodyne_points/data/*.bin, velodyne_points/timestamps{,_start,_end}.txt, oxts/data/*.txt,
/// oxts/dataformat.txt, oxts/timestamps.txt}`. Every file is written atomically. Velodyne scans
/// are written with io/velodyne.hpp (writeVelodyneBin).
#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "mapfuse/core/se3.hpp"
#include "mapfuse/geo/oxts.hpp"
#include "mapfuse/io/kitti_calib.hpp"

namespace mapfuse::io {

/// @brief `<root>/<date>/<date>_drive_<name>_sync`.
std::filesystem::path kittiDriveDir(const std::filesystem::path& root, const std::string& date,
                                    const std::string& name);

/// @brief Frame file stem: 10 digits, zero padded ("0000000042").
std::string kittiFrameName(int index);

/// @brief Writes the three calibration files of a date folder with the key layout and values of
/// the real KITTI 2011_09_26 calibration (cam_to_cam, velo_to_cam, imu_to_velo).
/// @throws IoError on write failure.
void writeKittiCalibration(const std::filesystem::path& date_dir);

/// @brief What readKittiCalibration reads back from the files writeKittiCalibration writes
/// (parsed from the same text, without the files: they may still be staged, io/output_transaction).
KittiCalibration writtenKittiCalibration();

/// @brief One OXTS line: 30 space-separated fields, doubles with 17 significant digits (so the
/// text parses back to the same double), the five status fields as integers.
std::string formatOxtsLine(const geo::OxtsRecord& record);

/// @brief Writes `oxts/dataformat.txt` exactly as KITTI ships it.
void writeOxtsDataformat(const std::filesystem::path& path);

/// @brief KITTI timestamp text "YYYY-MM-DD hh:mm:ss.nnnnnnnnn" for `seconds` after midnight of
/// `date` ("2011_09_26"), rounded to the nanosecond.
std::string formatKittiTimestamp(const std::string& date, double seconds);

/// @brief Writes lines (each followed by '\n').
void writeLines(const std::filesystem::path& path, const std::vector<std::string>& lines);

/// @brief Writes an 8-bit BGR image (width*height*3 bytes) as PNG.
/// @throws InputError when the size does not match; IoError on failure.
void writePngBgr(const std::filesystem::path& path, int width, int height,
                 const std::vector<uint8_t>& bgr);

/// The geographic anchor of a synthetic drive: world point `world_origin` (m, x east, y north,
/// z up) sits at (lat0, lon0, alt0), and the devkit Mercator scale is cos(lat0).
struct MercatorAnchor {
  double lat0 = 49.011212804408;                           ///< deg
  double lon0 = 8.4228850417969;                           ///< deg
  double alt0 = 112.83;                                    ///< m
  Eigen::Vector3d world_origin = Eigen::Vector3d::Zero();  ///< m
};

/// @brief Inverse of geo::oxtsToMercatorPose: the OXTS position/attitude whose devkit pose is
/// T_world_imu (translated by the anchor). At world_origin the result is exactly (lat0, lon0).
/// Velocities, accelerations and rates are left zero; status fields get typical RTK values.
geo::OxtsRecord oxtsFromPose(const Pose3& T_world_imu, const MercatorAnchor& anchor);

}  // namespace mapfuse::io
