#pragma once
/// @file A simulator World from a Lanelet2 map (docs/simulate.md "Lanelet2 maps"): drivable
/// lanelets become lanes (plus a reversed twin when one_way=no), successors come from shared
/// bound end points; line_thin / line_thick ways become lane lines, stop_line ways stop lines,
/// crosswalk lanelets crosswalks, traffic_sign ways sign quads, traffic_light ways lights.
/// The map has no arrows or poles: the simulator places arrows before stop lines and poles under
/// signs and lights, and says so in each instance's `note`.
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
