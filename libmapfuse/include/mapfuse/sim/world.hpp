#pragma once
/// @file The simulator's world (docs/simulate.md "Worlds"): a directed lane graph to drive on
/// and the true map elements (a VectorMap in ENU with stable ids). Both the Lanelet2 reader and
/// the procedural generator produce one.
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "mapfuse/core/input_warnings.hpp"
#include "mapfuse/core/vector_map.hpp"
#include "mapfuse/sim/polyline.hpp"

namespace mapfuse::sim {

/// One drivable lane in its driving direction.
struct Lane {
  int64_t id = 0;                       ///< unique; Lanelet2 lanelet id (negated twin for reverse)
  Polyline centerline;                  ///< ENU, in driving direction, m
  double width = 3.5;                   ///< m
  std::vector<std::size_t> successors;  ///< indices into World::lanes
};

/// Dashed lane line pattern (German urban "Leitlinie" 3 m dash / 6 m gap by default).
struct DashPattern {
  double dash = 3.0;  ///< m
  double gap = 6.0;   ///< m
};

struct World {
  std::string name;  ///< "procedural" or the map file
  std::vector<Lane> lanes;
  VectorMap truth;  ///< true elements, ENU of truth.origin
  DashPattern dashes;
  std::map<std::string, double> stats;  ///< counts reported in the summary
  InputWarnings warnings;  ///< what the map reader clamped, repaired or dropped (summary, stderr)
  /// Height of the road surface at an ENU point's (x, y), m, on the deck nearest in height to the
  /// point's z (bridges): a vehicle rolls with the road's cross-slope (simulateDrive). The
  /// procedural terrain is exact; map worlds fit it to their lanes (sim/lane_surface.hpp).
  /// Empty: each road is level across.
  std::function<double(const Eigen::Vector3d&)> surface_height;

  /// @brief Total centreline length of the lanes, m.
  double laneLength() const;
  /// @brief Appends a true element made by the world builder (its own source, `id`).
  /// @return the element, for its attributes.
  MapInstance& addTruth(int64_t id, CrowdClass cls, Polyline points, const std::string& note);
};

/// What a world holds, for the summary.
struct WorldSummary {
  std::string name;  ///< "procedural" or the map file
  std::size_t lanes = 0;
  double lane_km = 0.0;                          ///< lane centrelines
  std::size_t elements = 0;                      ///< true elements
  std::map<std::string, int> elements_by_class;  ///< by class name
  double lane_line_km = 0.0;                     ///< true lane lines
  std::map<std::string, double> stats;           ///< the world builder's counts
  InputWarnings warnings;                        ///< the map reader's, by kind
};

/// @brief Counts and lengths of a world's lanes and true elements.
WorldSummary summarize(const World& world);

/// @brief Connects lane a -> b when the end of a is within `tolerance` m of the start of b and
/// the directions agree within 60 degrees. Replaces existing successors.
void connectLanesByEndpoints(World& world, double tolerance);

/// @brief Observable pieces of a true instance: a solid line as one piece; a dashed line as one
/// piece per dash (DashPattern, phase 0 at the line start); every other element as itself.
/// Line pieces are resampled every `step` m.
std::vector<Polyline> observablePieces(const MapInstance& instance, const DashPattern& dashes,
                                       double step);

}  // namespace mapfuse::sim
