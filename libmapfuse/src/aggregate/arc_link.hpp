#pragma once
/// @file Stage-2 link test along a circular arc: does fragment b continue fragment a on a curve
/// too tight for the straight test (lane_instantiation.cpp)? Dashes of a roundabout ring
/// (radius ~9 m, 3 m dashes, 6 m gaps) turn ~60 deg from one dash to the next.
#include <Eigen/Core>
#include <vector>

namespace mapfuse::aggregate {

struct ArcLinkLimits {
  double max_gap = 8.0;        ///< m, arc length between the two ends
  double min_radius = 4.0;     ///< m, tighter circles are no lane line
  double max_residual = 0.15;  ///< m, largest distance of a tail point from the fitted circle
};

/// @param tail_a points of fragment a near its end, ordered towards the end (end last)
/// @param tail_b points of fragment b near its end, ordered away from the end (end first)
/// @return true when one circle (radius >= min_radius) fits both tails within max_residual,
///         b's end lies ahead of a's end along the circle within max_gap, and b goes on away
///         from a.
bool continuesOnArc(const std::vector<Eigen::Vector3d>& tail_a,
                    const std::vector<Eigen::Vector3d>& tail_b, const ArcLinkLimits& limits);

/// Points every `step` metres along the circle fitted to both tails, strictly between a's end
/// and b's end (height interpolated linearly); empty when the tails fit no circle. Fills the gap
/// of an arc link, which the centreline would otherwise bridge with a chord (0.5 m inside a
/// 9 m ring across a 6 m gap).
std::vector<Eigen::Vector3d> arcBridge(const std::vector<Eigen::Vector3d>& tail_a,
                                       const std::vector<Eigen::Vector3d>& tail_b, double step);

/// Least-squares circle through 2D points (algebraic fit, Kasa 1976); false when they are
/// (nearly) collinear or fewer than three.
bool fitCircle2d(const std::vector<Eigen::Vector2d>& pts, Eigen::Vector2d* centre, double* radius);

}  // namespace mapfuse::aggregate
