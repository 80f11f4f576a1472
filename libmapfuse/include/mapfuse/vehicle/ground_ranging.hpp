#pragma once
/// @file Ground element ranging (Song et al. 2023 §3.2.2, eq. 1): a marking pixel x is
/// back-projected onto the near-ground plane n^T X + h = 0 of the camera frame,
///   X = -h K^-1 x / (n^T K^-1 x),
/// and kept only inside a valid range band, with a per-point covariance propagated from pixel
/// noise, camera-height and attitude (pitch / roll) uncertainty.
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "mapfuse/core/param.hpp"
#include "mapfuse/vehicle/camera.hpp"

namespace mapfuse::vehicle {

/// Settings of eq. (1); each declared once, in visit().
struct RangingSettings {
  double min_range = 3.0;         ///< m, closest accepted point (distance from the camera)
  double max_range = 30.0;        ///< m, farthest accepted point
  double sigma_pixel = 1.0;       ///< px, 1-sigma pixel noise of a marking point
  double sigma_height = 0.03;     ///< m, 1-sigma camera height uncertainty
  double sigma_attitude = 0.003;  ///< rad, 1-sigma residual pitch and roll after calibration
  bool path_surface = true;       ///< range on the road ahead (vehicle/path_surface.hpp)
  /// m, farthest a point may lie aside of a frame abreast that the path reached by turning
  double path_max_offset = 15.0;

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("min_range", min_range, "m", "closest ranged ground point (eq. 1 band)", in(0, 1000));
    v("max_range", max_range, "m", "farthest ranged ground point (eq. 1 band)", gt(0) & le(10000));
    v.relation("max_range", max_range, max_range > min_range, "> min_range");
    v("sigma_pixel", sigma_pixel, "px", "marking pixel noise (covariances)", gt(0) & le(100));
    v("sigma_height", sigma_height, "m", "camera height uncertainty (covariances)", in(0, 10));
    v("sigma_attitude", sigma_attitude, "rad", "pitch/roll uncertainty (covariances)", in(0, 1));
    v("path_surface", path_surface, "",
      "range each ground pixel again on the plane raised to the road abreast of it, by the "
      "road's vertical bend that the drive's own heights show (crests, sags, ramps); off: the "
      "plane under the camera only");
    v("path_max_offset", path_max_offset, "m",
      "path_surface: farthest a ranged point may lie aside of the frame abreast where the path "
      "turned on the way there (else the plane under the camera is kept; along a straight path "
      "the band's max_range)",
      gt(0) & le(1000));
  }
};

/// @brief Eq. (1), Song et al. 2023: X = -h K^-1 x / (n^T K^-1 x) in the camera frame.
/// @return nullopt when the ray does not hit the plane in front of the camera.
std::optional<Eigen::Vector3d> backProjectToGround(const Eigen::Vector2d& pixel,
                                                   const Eigen::Matrix3d& K_inv,
                                                   const GroundPlane& plane);

/// A ranged ground point in the camera frame with its covariance.
struct GroundPoint {
  Eigen::Vector3d p_cam;    ///< m
  Eigen::Matrix3d cov_cam;  ///< m^2
};

/// @brief Eq. (1) plus the range band and first-order covariance (numerical Jacobian of eq. 1
/// w.r.t. pixel u, v, height, pitch and roll).
/// @return nullopt when the pixel is above the horizon or outside [min_range, max_range].
std::optional<GroundPoint> rangeGroundPixel(const Eigen::Vector2d& pixel, const Eigen::Matrix3d& K,
                                            const GroundPlane& plane,
                                            const RangingSettings& settings);

/// @brief Ranges every pixel of a polyline, dropping those outside the band.
std::vector<GroundPoint> rangeGroundPolyline(const std::vector<Eigen::Vector2d>& pixels,
                                             const Eigen::Matrix3d& K, const GroundPlane& plane,
                                             const RangingSettings& settings);

}  // namespace mapfuse::vehicle
