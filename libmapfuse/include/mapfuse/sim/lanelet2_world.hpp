#pragma once
/// @file A simulator World from a Lanelet2 map (docs/simulate.md "Lanelet2 maps"): drivable
/// lanelets become lanes (plus a reversed twin when one_way=no), successors come from shared
/// bound end points; line_thin / line_thick ways become lane lines (pieces sharing an end node
/// joined into one marking), stop_line ways stop lines, crosswalk lanelets crosswalks,
/// traffic_sign ways sign quads, traffic_light ways lights, closed `arrow` ways arrows and
/// `pole` nodes poles. Signs and lights with a `height` tag stand at their nodes' altitude;
/// without, their mounting is assumed. A map without arrows or poles gets them placed by the
/// simulator (arrows before stop lines, poles under signs and lights), as each instance's `note`
/// says. Ways without `type` (read as `virtual`) draw one warning per map.
#include "mapfuse/geo/origin.hpp"
#include "mapfuse/io/lanelet2_osm.hpp"
#include "mapfuse/sim/world.hpp"

namespace mapfuse::sim {

/// Heights the Lanelet2 example maps do not carry (no `height` / `ele` on signs and lights).
struct Lanelet2Assumptions {
  double sign_bottom = 2.0;        ///< m above the road
  double sign_size = 0.6;          ///< m, quad height
  double light_bottom = 2.8;       ///< m above the road
  double light_height = 0.9;       ///< m, housing
  double arrow_before_stop = 8.0;  ///< m, arrow centre before the end of a lane at a stop line
};

/// @brief Converts a parsed Lanelet2 map into a World in ENU of `origin`.
World worldFromLanelet2(const io::Lanelet2Map& map, const geo::GeoOrigin& origin,
                        const Lanelet2Assumptions& assumptions = {});

}  // namespace mapfuse::sim
