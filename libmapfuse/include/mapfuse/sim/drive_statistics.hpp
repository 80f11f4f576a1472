#pragma once
/// @file Measured error statistics of simulated drives, with the values the configured sigmas
/// predict, for simulate.summary.json (docs/simulate.md "Summary").
#include <vector>

#include "mapfuse/sim/drive.hpp"

namespace mapfuse::sim {

/// Window over which odometry drift is measured, m.
constexpr double kDriftWindow = 100.0;

struct DriveStatistics {
  double km = 0.0;
  int gps_fixes = 0, gps_outliers = 0, gps_inliers = 0;
  double gps_sq_sum = 0.0, gps_stamp_sum = 0.0;
  int drift_windows = 0;
  double drift_sq_sum = 0.0, drift_expected_sq_sum = 0.0;

  /// @brief Accumulates one drive; `keyframes` are sample indices of its keyframes.
  void add(const Drive& drive, const std::vector<std::size_t>& keyframes,
           const DriveParams& params);
  /// @brief Adds another's sums and counts.
  void add(const DriveStatistics& other);
  /// @brief m, RMS horizontal error of the fixes that are not multipath outliers.
  double gpsErrorRms() const;
  /// @brief m, what the configured bias, walk and noise predict for gpsErrorRms().
  double gpsErrorRmsExpected(const DriveParams& params) const;
  /// @brief m, RMS relative translation error per kDriftWindow m of odometry.
  double driftRms() const;
  /// @brief m, what the configured wheel and gyro errors predict for driftRms().
  double driftRmsExpected() const;
};

}  // namespace mapfuse::sim
