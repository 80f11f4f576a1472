#pragma once
/// @file Georeferencing of one LSM (§4.1, eq. (4)-(6), Song et al. 2023): a Ceres pose graph over
/// its keyframes with odometry relative-pose factors and GPS position factors, robust to multipath
/// (Cauchy loss, then explicit chi-square rejection and re-solve), with a tilt (gravity) prior per
/// keyframe from the odometry, whose frame has z up.
#include <string>
#include <vector>

#include "mapfuse/core/lsm.hpp"
#include "mapfuse/core/param.hpp"
#include "mapfuse/geo/origin.hpp"

namespace mapfuse::fusion {

/// Parameters of georef (docs/fusion.md); each declared once, in visit().
struct GeorefSettings {
  double odom_sigma_translation_per_m = 0.02;  ///< relative odometry sigma per metre travelled
  double odom_sigma_rotation_per_m = 0.001;    ///< rad per metre travelled
  double odom_min_sigma_translation = 0.02;    ///< m, floor of the relative sigma
  double odom_min_sigma_rotation = 0.002;      ///< rad, floor of the relative sigma
  /// rad, tilt prior per keyframe: roll and pitch as the odometry measured them (odom z is up);
  /// 0 leaves them to the GPS heights alone (a straight drive's roll is then unobservable)
  double gravity_sigma = 0.01;
  double gps_time_offset = 0.0;  ///< s, added to GPS stamps before association (receiver latency)
  double gps_max_extrapolation = 0.5;  ///< s, fixes further outside the keyframe span are dropped
  double cauchy_scale = 2.0;           ///< Cauchy loss scale on whitened GPS residuals (sigmas)
  double chi2_gate = 11.34;      ///< reject fixes with whitened squared residual above (3 dof, 99%)
  int max_rejection_rounds = 3;  ///< solve / reject / re-solve rounds
  int max_iterations = 100;      ///< Levenberg-Marquardt iterations per solve
  /// a drive whose GPS residual rms exceeds this many reported sigmas on an axis (horizontal
  /// or vertical) has odometry and GPS that disagree: named on stderr and in the summary
  double trust_sigma_ratio = 2.0;
  /// a drive whose share of rejected GPS fixes exceeds this is untrusted too: odometry that
  /// bends away from GPS gets the fixes it contradicts rejected as multipath, and the residual
  /// over the rest looks fine (gyro-only pitch on an 8 % world: 44 % rejected, 4 m residual)
  double trust_max_rejected_share = 0.1;
  /// |fused minus odometry height| growing faster than this per metre: a tilted dead reckoning
  /// (0.004 = 0.23 deg; an IMU pitched 0.5 deg gives 0.0087)
  double trust_max_vertical_slope = 0.004;
  /// |fused / odometry length - 1|: a wheel scale error beyond what wheel odometry shows (a few
  /// per cent; GPS corrects those), e.g. a wrong tyre radius or a slipping wheel
  double trust_max_scale_error = 0.05;

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("odom_sigma_translation_per_m", odom_sigma_translation_per_m, "m/m",
      "relative odometry translation sigma per metre travelled", in(0, 10));
    v("odom_sigma_rotation_per_m", odom_sigma_rotation_per_m, "rad/m",
      "relative odometry rotation sigma per metre travelled", in(0, 10));
    v("odom_min_sigma_translation", odom_min_sigma_translation, "m", "floor of odometry sigma",
      gt(0) & le(1000));
    v("odom_min_sigma_rotation", odom_min_sigma_rotation, "rad", "floor of odometry sigma",
      gt(0) & le(10));
    v("gravity_sigma", gravity_sigma, "rad",
      "tilt prior per keyframe from the odometry, whose z is up (0: none)", in(0, 10));
    v("gps_time_offset", gps_time_offset, "s", "added to GPS stamps before association",
      in(-3600, 3600));
    v("gps_max_extrapolation", gps_max_extrapolation, "s",
      "fixes further outside the keyframe span are dropped", in(0, 3600));
    v("cauchy_scale", cauchy_scale, "sigma", "Cauchy loss scale on whitened GPS residuals",
      gt(0) & le(1e6));
    v("chi2_gate", chi2_gate, "", "reject GPS fixes with whitened squared residual above",
      gt(0) & le(1e12));
    v("max_rejection_rounds", max_rejection_rounds, "", "solve / reject / re-solve rounds",
      in(1, 100));
    v("max_iterations", max_iterations, "", "Levenberg-Marquardt iterations per solve",
      in(1, 100000));
    v("trust_sigma_ratio", trust_sigma_ratio, "",
      "GPS residual rms per axis above this many reported sigmas: the drive is untrusted",
      gt(0) & le(1e6));
    v("trust_max_rejected_share", trust_max_rejected_share, "",
      "share of rejected GPS fixes above which the drive is untrusted", in(0, 1));
    v("trust_max_vertical_slope", trust_max_vertical_slope, "m/m",
      "fused minus odometry height slope above which the drive is untrusted", in(0, 1));
    v("trust_max_scale_error", trust_max_scale_error, "",
      "fused over odometry length minus 1 above which the drive is untrusted", in(0, 1));
  }
};

struct GeorefResult {
  Lsm lsm;  ///< keyframes in `enu` of the origin; elements unchanged (they ride their anchors)
  bool converged = false;
  int iterations = 0;  ///< summed over solves
  int gps_total = 0, gps_used = 0, gps_rejected = 0, gps_dropped = 0;
  std::vector<double> rejected_stamps;  ///< s, stamps of rejected fixes (multipath)
  double residual_mean = 0.0;    ///< m, horizontal+vertical GPS residual norm over accepted fixes
  double residual_rms = 0.0;     ///< m
  double residual_max = 0.0;     ///< m
  double residual_h_rms = 0.0;   ///< m, horizontal part of the GPS residual (accepted fixes)
  double residual_v_rms = 0.0;   ///< m, vertical part (fused height minus GPS altitude)
  double residual_v_mean = 0.0;  ///< m, signed mean of the vertical part (a height offset)
  double odom_vertical_slope = 0.0;  ///< m/m, slope of fused minus odometry height over distance
  double odom_scale_error = 0.0;     ///< median fused / odometry chord length minus 1
  bool trusted = true;      ///< every trust_* bound of GeorefSettings held (docs/fusion.md)
  double final_cost = 0.0;  ///< Ceres cost of the last solve
  double seconds = 0.0;     ///< wall time of this LSM (georeferenceLsms)
};

/// @brief Georeferences one LSM into ENU of `origin`.
/// @param lsm input (keyframes in odom, or already in enu: only relative motion is used)
/// @param origin the run's shared ENU origin
/// @param source file name for error messages
/// @throws InputError when the LSM has no keyframe or no usable GPS fix.
GeorefResult georeferenceLsm(const Lsm& lsm, const geo::GeoOrigin& origin,
                             const GeorefSettings& settings, const std::string& source);

/// @brief Georeferences every LSM into ENU of `origin`, `threads` at a time (one per LSM at
/// most). @param sources file names for error messages, one per LSM.
/// @throws the first error of any LSM (InputError when one cannot be georeferenced).
std::vector<GeorefResult> georeferenceLsms(const std::vector<Lsm>& lsms,
                                           const geo::GeoOrigin& origin,
                                           const GeorefSettings& settings,
                                           const std::vector<std::string>& sources, int threads);

/// @brief Relative odometry covariance between two consecutive keyframes: the growth of their
/// absolute standard deviations (diagonal; drift is systematic, so sigmas add, not variances),
/// bounded below by the distance-proportional model.
Matrix6d relativeOdometryCovariance(const Keyframe& a, const Keyframe& b, double sigma_t_per_m,
                                    double sigma_r_per_m, double min_sigma_t, double min_sigma_r);

}  // namespace mapfuse::fusion
