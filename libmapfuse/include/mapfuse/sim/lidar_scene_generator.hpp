#pragma once
/// @file Seeded procedural urban street for the LiDAR simulator (docs/lidar-ground-truth.md):
/// straight-turn-straight-turn-straight road, sidewalks with curbs, building facades, fences,
/// hedges, trees, poles with signs, parked cars and moving cars.
#include <cstdint>

#include "mapfuse/sim/lidar_scene.hpp"

namespace mapfuse::sim {

/// Everything the street generator uses (the stage's Params copy their values in here).
struct StreetParams {
  uint64_t seed = 1;
  RoadProfile profile;
  double straight_min = 60.0;         ///< m
  double straight_max = 110.0;        ///< m
  double turn_radius_min = 18.0;      ///< m
  double turn_radius_max = 30.0;      ///< m
  double building_share = 0.55;       ///< probability a frontage segment is a building
  double fence_share = 0.25;          ///< probability of a fence (else a hedge)
  double building_height_min = 6.0;   ///< m
  double building_height_max = 18.0;  ///< m
  double pole_spacing = 25.0;         ///< m, mean distance between poles per side
  double tree_spacing = 18.0;         ///< m, mean distance between sidewalk trees per side
  double parked_share = 0.5;          ///< share of the right curb with parking stretches
  int moving_vehicles = 6;            ///< cars driving along the road
  double ego_start = 25.0;            ///< m, arc length where the ego drive starts
  double ego_speed = 8.0;             ///< m/s, ego speed (moving cars avoid the ego lane near it)
};

/// @brief Generates the street. Same params => same scene.
LidarScene generateStreet(const StreetParams& params);

}  // namespace mapfuse::sim
