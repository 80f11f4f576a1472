#pragma once
/// @file Stage `georef` (§4.1, eq. (4)-(6), Song et al. 2023): each LSM's keyframes are fused with
/// its GPS fixes in a Ceres pose graph and written in ENU of one origin shared by the whole run.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mapfuse/cli/params.hpp"
#include "mapfuse/fusion/georef.hpp"

namespace mapfuse::stages {

struct GeorefParams {
  std::string origin;  ///< "lat,lon,alt"; empty = first GPS fix of the first LSM
  double odom_sigma_translation_per_m = 0.02;
  double odom_sigma_rotation_per_m = 0.001;
  double odom_min_sigma_translation = 0.02;
  double odom_min_sigma_rotation = 0.002;
  double gravity_sigma = 0.01;
  double gps_time_offset = 0.0;
  double gps_max_extrapolation = 0.5;
  double cauchy_scale = 2.0;
  double chi2_gate = 11.34;
  int max_rejection_rounds = 3;
  int max_iterations = 100;
  int threads = 2;

  template <class V>
  void visit(V& v) {
    v("origin", origin, "deg,deg,m", "shared ENU origin lat,lon,alt (empty: first GPS fix)");
    v("odom_sigma_translation_per_m", odom_sigma_translation_per_m, "m/m",
      "relative odometry translation sigma per metre travelled");
    v("odom_sigma_rotation_per_m", odom_sigma_rotation_per_m, "rad/m",
      "relative odometry rotation sigma per metre travelled");
    v("odom_min_sigma_translation", odom_min_sigma_translation, "m", "floor of odometry sigma");
    v("odom_min_sigma_rotation", odom_min_sigma_rotation, "rad", "floor of odometry sigma");
    v("gravity_sigma", gravity_sigma, "rad",
      "tilt prior per keyframe from the odometry, whose z is up (0: none)");
    v("gps_time_offset", gps_time_offset, "s", "added to GPS stamps before association");
    v("gps_max_extrapolation", gps_max_extrapolation, "s",
      "fixes further outside the keyframe span are dropped");
    v("cauchy_scale", cauchy_scale, "sigma", "Cauchy loss scale on whitened GPS residuals");
    v("chi2_gate", chi2_gate, "", "reject GPS fixes with whitened squared residual above");
    v("max_rejection_rounds", max_rejection_rounds, "", "solve / reject / re-solve rounds");
    v("max_iterations", max_iterations, "", "Levenberg-Marquardt iterations per solve");
    v("threads", threads, "", "OpenMP threads over LSMs");
  }
  void validate() const;
  fusion::GeorefSettings settings() const;
};

/// @brief Parses "lat,lon,alt". @throws ConfigError naming the value.
geo::GeoOrigin parseOrigin(const std::string& text);

/// @brief Georeferences every input LSM; writes <out_dir>/<same file name> for each (atomically,
/// only after all succeeded), georef.config.json and georef.summary.json.
/// @return the summary JSON.
/// @throws IoError, ParseError, InputError (exit 3) for unusable inputs.
nlohmann::json runGeoref(const std::vector<std::string>& inputs,
                         const std::filesystem::path& out_dir, const GeorefParams& params);

}  // namespace mapfuse::stages
