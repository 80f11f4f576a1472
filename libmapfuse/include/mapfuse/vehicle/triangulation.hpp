#pragma once
/// @file Aerial element ranging (Song et al. 2023 §3.2.3, eq. 2-3): the 3D position of a
/// tracked element (sign, light, pole) from its pixel observations in several frames with
/// ego-motion baselines. Linear (DLT) initialisation, then Ceres Levenberg-Marquardt on the
/// reprojection error with a Huber loss (eq. 3); tracks with too little parallax are rejected.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "mapfuse/core/param.hpp"
#include "mapfuse/core/se3.hpp"

namespace mapfuse::vehicle {

/// One pixel observation of a tracked element.
struct TrackObservation {
  Pose3 T_world_cam;      ///< camera pose when observed (world = odom)
  Eigen::Vector2d pixel;  ///< px
};

/// Settings of eq. (2)-(3); the parameters declared once, in visit().
struct TriangulationSettings {
  double min_parallax = 0.02;         ///< rad, largest angle between two observation rays
  int min_observations = 3;           ///< frames
  double sigma_pixel = 1.0;           ///< px, observation 1-sigma (scales the residuals)
  double huber_delta = 2.0;           ///< in sigmas, Huber loss threshold (robust loss of eq. 3)
  double max_reprojection_rms = 4.0;  ///< px, tracks fitting worse are rejected
  double max_range = 30.0;            ///< m, > 0: tracks never seen closer than this are rejected
  int max_iterations = 30;            ///< Levenberg-Marquardt iterations
  /// m: triangulated tracks of one class closer than this (horizontally) are one element seen by
  /// two detectors or as two broken tracks: the one with more frames is kept; 0 = off
  double duplicate_radius = 1.0;

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("min_parallax", min_parallax, "rad", "aerial tracks with less parallax are rejected",
      in(0, 3.2));
    v("min_track_frames", min_observations, "", "frames needed to triangulate a track",
      in(2, 100000));
    v("track_sigma_pixel", sigma_pixel, "px", "aerial key-point noise", gt(0) & le(100));
    v("huber_delta", huber_delta, "sigma", "robust loss threshold of the triangulation",
      gt(0) & le(1e6));
    v("max_reprojection_rms", max_reprojection_rms, "px", "worse tracks are rejected",
      gt(0) & le(1e6));
    v("max_track_range", max_range, "m", "aerial tracks never seen closer are rejected",
      gt(0) & le(100000));
    v("triangulation_iterations", max_iterations, "",
      "Levenberg-Marquardt iterations of one track's triangulation (eq. 3)", in(1, 10000));
    v("duplicate_radius", duplicate_radius, "m",
      "triangulated aerial elements of one class closer than this are one (the element seen in "
      "more frames is kept); 0 = off",
      in(0, 100));
  }
};

/// Outcome of one track.
struct TriangulationResult {
  bool ok = false;
  std::string reason;  ///< why rejected ("parallax", "observations", ...)
  Eigen::Vector3d p_world = Eigen::Vector3d::Zero();         ///< m
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();  ///< m^2, (J^T J)^-1 sigma^2
  double parallax = 0.0;                                     ///< rad
  double nearest_range = 0.0;  ///< m, closest camera-to-element distance of the track
  double rms = 0.0;            ///< px, final reprojection RMS
  int iterations = 0;
  bool converged = false;
};

/// @brief Linear triangulation (DLT, eq. 2 stacked over frames); the starting point of LM.
Eigen::Vector3d triangulateLinear(const Eigen::Matrix3d& K,
                                  const std::vector<TrackObservation>& obs);

/// @brief Eq. (2)-(3), Song et al. 2023: argmin_P sum_i rho(|pi(K, T_cam_i_world P) - x_i|^2).
TriangulationResult triangulateTrack(const Eigen::Matrix3d& K,
                                     const std::vector<TrackObservation>& obs,
                                     const TriangulationSettings& settings);

}  // namespace mapfuse::vehicle
