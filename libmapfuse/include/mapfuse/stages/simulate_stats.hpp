#pragma once
/// @file Measured error statistics of simulated drives, with the values the configured sigmas
/// predict, for simulate.summary.json (docs/simulate.md "Summary").
#include <nlohmann/json.hpp>
#include <vector>

#include "mapfuse/sim/drive.hpp"

namespace mapfuse::stages {

/// Window over which odometry drift is measured, m.
constexpr double kDriftWindow = 100.0;

struct DriveStatistics {
  double km = 0.0;
  int gps_fixes = 0, gps_outliers = 0, gps_inliers = 0;
  double gps_sq_sum = 0.0, gps_stamp_sum = 0.0;
  int drift_windows = 0;
  double drift_sq_sum = 0.0, drift_expected_sq_sum = 0.0;

  /// @brief Accumulates one drive; `keyframes` are sample indices of its keyframes.
  void add(const sim::Drive& drive, const std::vector<std::size_t>& keyframes,
           const sim::DriveParams& params);
  /// @brief gps_error_rms_m (non-outlier fixes, horizontal) and its expectation, and
  /// odometry_drift_per_100m_rms_m (relative translation error per 100 m) and its expectation.
  nlohmann::json toJson(const sim::DriveParams& params) const;
};

}  // namespace mapfuse::stages
