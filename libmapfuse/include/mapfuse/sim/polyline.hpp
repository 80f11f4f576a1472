#pragma once
/// @file Polyline helpers of the simulator: arc-length resampling, offsetting, interpolation.
#include <Eigen/Core>
#include <vector>

namespace mapfuse::sim {

using Polyline = std::vector<Eigen::Vector3d>;

/// @brief Cumulative arc length at every vertex (first = 0), m.
std::vector<double> arcLengths(const Polyline& line);

/// @brief Point at arc length s (clamped to [0, length]) by linear interpolation.
/// @param cumulative arcLengths(line), passed to avoid recomputing it.
Eigen::Vector3d pointAt(const Polyline& line, const std::vector<double>& cumulative, double s);

/// @brief Resamples at (about) `step` metres, end points kept; fewer than 2 points are returned
/// unchanged.
Polyline resample(const Polyline& line, double step);

/// @brief Part of the line between arc lengths s0 < s1, resampled at `step`.
Polyline subLine(const Polyline& line, double s0, double s1, double step);

/// @brief subLine with the line's arc lengths given: cutting many parts from one line (the
/// dashes of a lane line) costs O(parts x (points per part + log n)), not O(parts x n).
/// @param cumulative arcLengths(line).
Polyline subLine(const Polyline& line, const std::vector<double>& cumulative, double s0, double s1,
                 double step);

/// @brief Offsets a line sideways in the xy plane by `offset` metres (positive = left of the
/// direction of travel), using vertex normals (averaged neighbouring segment directions).
Polyline offsetLine(const Polyline& line, double offset);

/// @brief Unit left normal (xy plane) of the direction at vertex i (central difference).
Eigen::Vector3d leftNormalAt(const Polyline& line, std::size_t i);

/// @brief The reversed line.
Polyline reversed(Polyline line);

/// @brief Moving-average smoothing of the interior vertices (`half_window` neighbours each
/// side, `passes` times); end points stay fixed.
Polyline smooth(const Polyline& line, int half_window, int passes);

/// @brief Distance from p to the polyline in 3D, m.
double distanceToPolyline(const Polyline& line, const Eigen::Vector3d& p);

/// @brief Distance from p (xy only) to a closed polygon's region: 0 inside.
double distanceToPolygonXY(const Polyline& ring, const Eigen::Vector3d& p);

}  // namespace mapfuse::sim
