#pragma once
/// @file Seeded procedural world (docs/simulate.md "Procedural world"): a jittered grid of
/// intersections joined by curved two-way roads with 1..N lanes per direction, one fork and
/// merge (a bypass lane), stop lines, ground arrows, crosswalks, signs, traffic lights and poles.
#include <cstdint>

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
};

/// @brief Builds the procedural world around `origin` (ENU, flat road surface z = 0).
/// @throws ConfigError when the grid is too small for the radius.
World buildProceduralWorld(const ProceduralParams& params, const geo::GeoOrigin& origin,
                           uint64_t seed);

}  // namespace mapfuse::sim
