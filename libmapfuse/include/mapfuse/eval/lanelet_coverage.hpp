#pragma once
/// @file How much of the true lanes a Lanelet2 map's lanelets cover (docs/formats.md "Lanelet2
/// export", scripts/bench/bench_lanelets.sh): each true lane is sampled along its centre line;
/// a sample counts where the vector map has a lane line on both sides of it (within a tolerance
/// of the lane's borders: a lanelet with both bounds is possible there), and is covered when it
/// lies inside a lanelet (which always has both bounds), with the lanelet's travel direction
/// compared to the lane's.
#include <Eigen/Core>
#include <vector>

#include "mapfuse/core/vector_map.hpp"
#include "mapfuse/geo/origin.hpp"
#include "mapfuse/io/lanelet2_osm.hpp"

namespace mapfuse::eval {

/// A true lane: centre line in its driving direction (ENU, m) and width (m).
struct TrueLane {
  std::vector<Eigen::Vector3d> centre;
  double width = 3.5;
};

/// A lanelet of a Lanelet2 file in ENU.
struct LaneletShape {
  std::vector<Eigen::Vector3d> ring;    ///< left bound, then the right bound reversed
  std::vector<Eigen::Vector3d> centre;  ///< in the travel direction (left bound on the left)
  bool one_way = true;                  ///< false: `one_way=no` (direction unknown)
};

/// @brief The road lanelets (not crosswalks) of a parsed Lanelet2 map, in ENU of `origin`.
std::vector<LaneletShape> laneletShapes(const io::Lanelet2Map& osm, const geo::GeoOrigin& origin);

struct LaneletCoverage {
  double lane_m = 0.0;      ///< true lane length sampled
  double marked_m = 0.0;    ///< ... with a map lane line near both borders
  double covered_m = 0.0;   ///< ... of it inside a lanelet
  double directed_m = 0.0;  ///< ... inside a one-way lanelet driven the lane's way
  double reversed_m = 0.0;  ///< ... inside one-way lanelets only, all of them the other way
  double share() const { return marked_m > 0 ? covered_m / marked_m : 0.0; }
  double directedShare() const { return marked_m > 0 ? directed_m / marked_m : 0.0; }
};

/// @brief Samples every `step` m of the true lanes; a sample is marked when a lane line of
/// `map` lies within `tolerance` m of both points half a lane width to its sides.
LaneletCoverage measureLaneletCoverage(const std::vector<TrueLane>& lanes, const VectorMap& map,
                                       const std::vector<LaneletShape>& lanelets, double step = 1.0,
                                       double tolerance = 1.0);

}  // namespace mapfuse::eval
