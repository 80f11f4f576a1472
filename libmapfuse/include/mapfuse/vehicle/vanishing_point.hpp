#pragma once
/// @file Ground-plane calibration from lane vanishing points (Song et al. 2023 §3.2.1).
/// Parallel lane lines meet in the image at the vanishing point v; its ray d = K^-1 v is a
/// direction lying in the road plane, so the ground normal must satisfy n^T d = 0. Rotating
/// the nominal normal about the camera x axis until it does gives the pitch correction; a
/// second vanishing direction (stop lines, crosswalk edges) also fixes roll: n ~ d1 x d2.
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "mapfuse/core/param.hpp"
#include "mapfuse/vehicle/camera.hpp"

namespace mapfuse::vehicle {

/// Settings of the vanishing-point calibration; the parameters declared once, in visit().
struct VanishingSettings {
  bool enabled = true;        ///< correct the ground plane from lane vanishing points
  int window = 601;           ///< frames in the median window (the mount error is constant)
  double max_range = 25.0;    ///< m, lane points farther away are not fitted; also the look-ahead
  double max_line_rms = 1.5;  ///< px, lines fitting worse (curves) are rejected
  double max_pitch_correction = 0.05;  ///< rad, larger corrections are rejected as outliers
  int min_points_per_line = 8;         ///< pixels needed to fit one lane line
  double min_line_angle = 0.05;        ///< rad, lines must differ this much in image direction
  double max_heading_change = 0.004;   ///< rad, ego heading change over the look-ahead (straight)
  double max_azimuth_error = 0.01;     ///< rad, VP azimuth vs ego-motion direction over look-ahead
  double max_pitch_change = 0.004;     ///< rad, grade change over the look-ahead (no crest/sag)
  int min_frames = 50;                 ///< accepted frames needed, else the static extrinsic
  double min_significance = 3.0;       ///< |median| / its standard error needed to correct

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("vp_calibration", enabled, "", "vanishing-point ground-plane calibration");
    v("vp_window", window, "frames", "median window of the pitch correction", in(1, 1000000));
    v("vp_max_range", max_range, "m",
      "lane points farther than this are not fitted; the ego-motion look-ahead of the "
      "straightness and direction tests",
      gt(0) & le(1000));
    v("vp_max_line_rms", max_line_rms, "px", "straightness required of a fitted lane",
      gt(0) & le(1000));
    v("max_pitch_correction", max_pitch_correction, "rad", "larger corrections are outliers",
      gt(0) & le(1));
    v("vp_min_points_per_line", min_points_per_line, "px",
      "lane pixels needed to fit one line of the vanishing point", in(2, 100000));
    v("vp_min_line_angle", min_line_angle, "rad",
      "the fitted lines must differ this much in image direction", gt(0) & le(1.6));
    v("vp_max_heading_change", max_heading_change, "rad",
      "frames whose ego heading turns more than this over the next vp_max_range metres (a curve) "
      "are not used",
      gt(0) & le(3.2));
    // On esmini tunnels (grades changing 0.07-0.1 over 70 m) the lines of a straight road into a
    // sag vanish above the horizon of the plane under the car: 18 of 20 drives took a 0.016-0.020
    // rad pitch correction from it, ranged 10-18 % short and mapped the outer lines 0.7 m inward.
    v("vp_max_pitch_change", max_pitch_change, "rad",
      "frames whose path grade changes more than this over the next vp_max_range metres (a crest "
      "or a sag: the lines ahead do not lie in the plane under the car) are not used",
      gt(0) & le(3.2));
    v("vp_max_azimuth_error", max_azimuth_error, "rad",
      "frames whose vanishing point's azimuth differs more than this from the ego-motion "
      "direction over the look-ahead (after the drive's median difference) are not used",
      gt(0) & le(3.2));
    v("vp_min_frames", min_frames, "frames",
      "fewer accepted frames: the static extrinsic is kept (fallback)", in(1, 1000000));
    v("vp_min_significance", min_significance, "",
      "the drive's median correction must exceed this many standard errors, else the static "
      "extrinsic is kept (0: always correct)",
      in(0, 1000));
  }
};

/// One frame's vanishing-point estimate.
struct VanishingEstimate {
  double pitch = 0.0;  ///< rad, correction of the nominal plane
  Eigen::Vector3d direction_cam = Eigen::Vector3d::UnitZ();  ///< unit vanishing direction
  int lines = 0;                                             ///< straight lane lines intersected
};

/// A homogeneous image line l (l^T x = 0, (l0, l1) unit) with its fit RMS.
struct ImageLine {
  Eigen::Vector3d l;
  double rms = 0.0;  ///< px
};

/// @brief Total-least-squares line through pixels; nullopt with fewer than 2 points.
std::optional<ImageLine> fitImageLine(const std::vector<Eigen::Vector2d>& pixels);

/// @brief Least-squares intersection of >= 2 lines: the unit v minimising sum (l_i^T v)^2.
/// @return homogeneous vanishing point (may be at infinity), nullopt when the lines are
/// (nearly) parallel in the image or fewer than 2.
std::optional<Eigen::Vector3d> vanishingPoint(const std::vector<ImageLine>& lines,
                                              double min_line_angle);

/// @brief Pitch (rad, about the camera x axis, tiltNormal convention) that makes the normal
/// perpendicular to the vanishing direction d; nullopt when impossible.
std::optional<double> pitchFromVanishingDirection(const Eigen::Vector3d& normal_cam,
                                                  const Eigen::Vector3d& direction_cam);

/// @brief One frame: fits the lane polylines (pixels), intersects them and returns the pitch
/// correction of the nominal plane with the vanishing direction; nullopt when fewer than two
/// usable straight lines or the correction exceeds max_pitch_correction.
std::optional<VanishingEstimate> estimateVanishing(
    const std::vector<std::vector<Eigen::Vector2d>>& lane_pixels, const Eigen::Matrix3d& K,
    const GroundPlane& nominal, const VanishingSettings& settings);

/// @brief estimateVanishing's pitch only.
std::optional<double> estimatePitchCorrection(
    const std::vector<std::vector<Eigen::Vector2d>>& lane_pixels, const Eigen::Matrix3d& K,
    const GroundPlane& nominal, const VanishingSettings& settings);

/// @brief The lane-line pixels of one frame that the calibration fits: those ranged on the
/// nominal plane within [min_range, max_range], grouped by their lateral offset so that the
/// dashes of one dashed line are fitted as one line.
std::vector<std::vector<Eigen::Vector2d>> laneLinePixels(const FrameObservations& frame,
                                                         const Eigen::Matrix3d& K_inv,
                                                         const GroundPlane& nominal,
                                                         double min_range, double max_range);

/// @brief Ground normal from two vanishing directions in the road plane (pitch and roll):
/// n ~ d1 x d2, oriented like `nominal`; nullopt when the directions are nearly parallel.
std::optional<Eigen::Vector3d> normalFromTwoDirections(const Eigen::Vector3d& d1,
                                                       const Eigen::Vector3d& d2,
                                                       const Eigen::Vector3d& nominal);

/// @brief Median of the per-frame corrections over a centred window of `window` frames;
/// frames without an estimate borrow their neighbours' (0 when none in the window).
std::vector<double> smoothCorrections(const std::vector<std::optional<double>>& per_frame,
                                      int window);

}  // namespace mapfuse::vehicle
