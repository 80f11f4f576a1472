#pragma once
/// @file Kinks of a lane line that would bound a lanelet (docs/formats.md "Lanelet2 export"):
/// an aggregated polyline can bend back on itself where Bezier pieces join or two observations
/// overlap (turns of 150-170 degrees over 0.05-0.5 m in the demo map). Lanelet2's validator
/// (mapping.curvature_too_big) flags every bound vertex whose Menger curvature, 4 * area / (product
/// of the three sides) of it and its two neighbours, exceeds 0.5 1/m; no painted lane bends that
/// tightly, so such vertices are artefacts and are dropped.
#include <Eigen/Core>
#include <vector>

#include "mapfuse/lanelet/plan.hpp"

namespace mapfuse::lanelet::detail {

/// What removeKinks did to one line.
struct KinkRemoval {
  int removed = 0;             ///< vertices dropped
  double max_deviation = 0.0;  ///< m: farthest dropped vertex from the line that remains (xy)
};

/// @brief Menger curvature (1/m, xy) at b of the triangle a, b, c; infinite when two of the
/// points coincide (as Lanelet2's curvature2d).
double mengerCurvature(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                       const Eigen::Vector3d& c);

/// @brief Drops interior vertices, the sharpest first, until every interior vertex has a Menger
/// curvature of at most `max_curvature` (1/m) and no vertex turns the line back (its two
/// segments more than 90 degrees apart). The end points stay.
std::vector<Eigen::Vector3d> removeKinks(const std::vector<Eigen::Vector3d>& line,
                                         double max_curvature, KinkRemoval* stats = nullptr);

/// @brief removeKinks on every piece of every plan line, the cut points kept: a piece's first
/// and last interior vertices see a shorter chord than on the whole line (the cut lies between
/// them and the line's previous vertex), so their curvature can exceed the limit again. Adds to
/// the plan's kink counters.
void removePieceKinks(LaneletPlan& plan, double max_curvature);

}  // namespace mapfuse::lanelet::detail
