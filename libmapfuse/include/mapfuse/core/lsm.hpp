#pragma once
/// @file The local semantic map (LSM): what one vehicle uploads for one drive
/// (DESIGN.md "The LSM"). Elements are anchored to keyframes and store their points in the
/// anchor's body frame, so moving a keyframe moves its elements rigidly (P' = R P + t, §4.2).
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mapfuse/core/classes.hpp"
#include "mapfuse/core/lat_lon_alt.hpp"
#include "mapfuse/core/se3.hpp"

namespace mapfuse {

/// Frame the keyframe poses are expressed in.
enum class LsmFrame : uint8_t {
  kOdom,  ///< the drive's own odometry frame (as uploaded by lsm-build / simulate)
  kEnu,   ///< ENU of `Lsm::origin` (after georef / align)
};

struct Keyframe {
  int64_t id = 0;                                     ///< unique within the LSM
  double stamp = 0.0;                                 ///< s
  Pose3 T_frame_body = Pose3::Identity();             ///< body pose in the LSM frame (odom or enu)
  Matrix6d covariance = Matrix6d::Identity() * 1e-4;  ///< of T_frame_body, (rho, phi) order
};

struct GpsFix {
  double stamp = 0.0;       ///< s
  geo::LatLonAlt position;  ///< WGS84
  double sigma_h = 1.0;     ///< horizontal 1-sigma, m
  double sigma_v = 2.0;     ///< vertical 1-sigma, m
};

struct Element {
  int64_t id = 0;  ///< unique within the LSM
  CrowdClass cls = CrowdClass::kLaneLine;
  Attributes attributes;
  int64_t anchor = 0;                        ///< Keyframe::id of the anchor
  std::vector<Eigen::Vector3d> points_body;  ///< in the anchor's body frame, m
  std::vector<Eigen::Matrix3d> covariances;  ///< per point, body frame, m^2 (same size)
  double confidence = 1.0;                   ///< [0, 1]
  int observations = 1;                      ///< frames that observed it
  double height = 0.0;    ///< m; pole / traffic light: vertical extent above the point
  int64_t truth_id = -1;  ///< simulator only: id of the true element (-1 = unknown/false)
};

struct Lsm {
  std::string drive_id;
  std::string vehicle_id;
  LsmFrame frame = LsmFrame::kOdom;
  std::optional<geo::GeoOrigin> origin;  ///< required when frame == kEnu
  std::vector<Keyframe> keyframes;       ///< sorted by stamp
  std::vector<GpsFix> gps;               ///< sorted by stamp
  std::vector<Element> elements;

  /// @brief Index of the keyframe with `id`; throws InputError when absent.
  std::size_t keyframeIndex(int64_t id) const;
  /// @brief Element points in the LSM frame (T_frame_body of the anchor applied).
  std::vector<Eigen::Vector3d> pointsInFrame(const Element& e) const;
};

/// @brief Checks internal consistency (anchors exist, sizes match, ids unique, origin present
/// for ENU, finite values). @throws InputError naming `source` and the problem.
void validateLsm(const Lsm& lsm, const std::string& source);

}  // namespace mapfuse
