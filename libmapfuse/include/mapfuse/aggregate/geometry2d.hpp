#pragma once
/// @file Small 2D helpers shared by the aggregation and evaluation code (EN plane of ENU):
/// polyline resampling, point-to-polyline distance, principal-axis binning.
#include <Eigen/Core>
#include <vector>

namespace mapfuse::aggregate {

/// @brief Points every `step` metres along a polyline (both ends included).
std::vector<Eigen::Vector3d> resamplePolyline(const std::vector<Eigen::Vector3d>& points,
                                              double step);

/// @brief Horizontal (EN) distance from p to the segment [a, b]; `foot` receives the closest
/// point (3D, z interpolated) when not null.
double distanceToSegment2d(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                           const Eigen::Vector3d& b, Eigen::Vector3d* foot = nullptr);

/// @brief Horizontal distance from p to a polyline (a single point counts as a polyline).
double distanceToPolyline2d(const Eigen::Vector3d& p, const std::vector<Eigen::Vector3d>& line,
                            Eigen::Vector3d* foot = nullptr);

/// @brief Unit principal direction (EN plane) of a point set; +x when degenerate.
Eigen::Vector2d principalAxis2d(const std::vector<Eigen::Vector3d>& points);

/// @brief Centreline of a point cloud spread along a line: points are projected on the
/// principal axis, averaged (3D mean) in bins of `step` metres, empty bins skipped.
std::vector<Eigen::Vector3d> binnedCentreline(const std::vector<Eigen::Vector3d>& points,
                                              double step);

}  // namespace mapfuse::aggregate
