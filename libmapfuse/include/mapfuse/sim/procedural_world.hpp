#pragma once
/// @file Seeded procedural world (docs/simulate.md "Procedural world"): a jittered grid of
/// intersections joined by curved two-way roads with 1..N lanes per direction, one fork and
/// merge (a bypass lane), stop lines, ground arrows, crosswalks, signs, traffic lights and poles.
#include <cstdint>

#include "mapfuse/core/param.hpp"
#include "mapfuse/geo/origin.hpp"
#include "mapfuse/sim/world.hpp"

namespace mapfuse::sim {

struct ProceduralParams {
  int grid_size = 3;                    ///< intersections per side (>= 2)
  double block_length = 220.0;          ///< m between neighbouring intersection centres
  double jitter = 10.0;                 ///< m, random shift of each intersection
  double curve_amplitude = 25.0;        ///< m, max lateral bulge of a road
  double lane_width = 3.5;              ///< m
  int max_lanes_per_direction = 2;      ///< lanes per direction are drawn in [1, this]
  double intersection_radius = 16.0;    ///< m from an intersection centre to its stop lines
  double traffic_light_fraction = 0.5;  ///< share of intersections with traffic lights
  double crosswalk_probability = 0.5;   ///< per intersection arm without lights
  double pole_spacing = 60.0;           ///< m between street-lamp poles along a road side
  double hill_grade = 0.0;              ///< max grade along a grid axis (0: a flat world)
  double hill_wavelength = 800.0;       ///< m, wavelength of the terrain's hills

  template <class V>
  void visit(V& v) {
    using namespace param;
    // the world holds grid_size^2 intersections
    v("world_grid_size", grid_size, "", "procedural: intersections per side", in(2, 50));
    v("world_block_length", block_length, "m", "procedural: intersection spacing",
      gt(0) & le(10000));
    v("world_jitter", jitter, "m", "procedural: random shift of intersections", in(0, 1000));
    v("world_curve_amplitude", curve_amplitude, "m", "procedural: max road bulge", in(0, 1000));
    v("world_lane_width", lane_width, "m", "procedural: lane width", gt(2) & le(10));
    v("world_max_lanes_per_direction", max_lanes_per_direction, "",
      "procedural: lanes per direction in [1, this]", in(1, 4));
    v("world_intersection_radius", intersection_radius, "m", "procedural: centre to stop line",
      gt(0) & le(1000));
    v("world_traffic_light_fraction", traffic_light_fraction, "",
      "procedural: share of intersections with lights", in(0, 1));
    v("world_crosswalk_probability", crosswalk_probability, "",
      "procedural: crosswalk per arm without lights", in(0, 1));
    v("world_pole_spacing", pole_spacing, "m", "procedural: street-lamp spacing",
      gt(5) & le(100000));
    // terrain z = A (sin(kx + a) + sin(ky + b)), k = 2 pi / wavelength, A = grade / k: a road
    // along a grid axis climbs at most `grade`, crosses its crests and sags every half
    // wavelength and leans across by up to `grade` where the other term slopes (cross-slope)
    v("world_hill_grade", hill_grade, "", "procedural: max terrain grade along a grid axis",
      in(0, 0.3));
    v("world_hill_wavelength", hill_wavelength, "m", "procedural: wavelength of the hills",
      gt(50) & le(100000));
  }
};

/// @brief Builds the procedural world around `origin` (ENU; the road surface is the terrain,
/// z = 0 when hill_grade is 0; elements keep their heights above it).
/// @throws ConfigError when the grid is too small for the radius.
World buildProceduralWorld(const ProceduralParams& params, const geo::GeoOrigin& origin,
                           uint64_t seed);

}  // namespace mapfuse::sim
