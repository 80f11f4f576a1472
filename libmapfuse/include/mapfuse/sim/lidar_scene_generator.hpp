#pragma once
/// @file Seeded procedural urban street for the LiDAR simulator (docs/lidar-ground-truth.md):
/// straight-turn-straight-turn-straight road, sidewalks with curbs, building facades, fences,
/// hedges, trees, poles with signs, parked cars and moving cars.
#include <cstdint>

#include "mapfuse/core/param.hpp"
#include "mapfuse/sim/lidar_scene.hpp"

namespace mapfuse::sim {

/// Everything the street generator uses but its seed (the drive's, generateStreet's argument);
/// the parameters declared once, in visit().
struct StreetParams {
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

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("ego_speed", ego_speed, "m/s", "speed of the ego vehicle", in(0, 100));
    v("ego_start", ego_start, "m", "arc length on the road of frame 0", in(0, 100000));
    v("road_half_width", profile.road_half_width, "m", "centreline to curb", gt(0) & le(100));
    v("sidewalk_width", profile.sidewalk_width, "m", "curb to property line", gt(0) & le(100));
    v("curb_height", profile.curb_height, "m", "sidewalk height above the road", in(0, 10));
    v("lane_width", profile.lane_width, "m",
      "lane width (ego and moving cars drive on lane centres)", gt(0) & le(100));
    v.relation("lane_width", profile.lane_width, profile.lane_width <= profile.road_half_width,
               "<= road_half_width");
    // the road (three straights, two turns) holds the primitives placed along it
    v("straight_min", straight_min, "m", "shortest of the three straights", gt(0) & le(10000));
    v("straight_max", straight_max, "m", "longest of the three straights", gt(0) & le(10000));
    v.relation("straight_min", straight_min, straight_min <= straight_max, "<= straight_max");
    v("turn_radius_min", turn_radius_min, "m", "smallest turn radius", gt(0) & le(10000));
    v("turn_radius_max", turn_radius_max, "m", "largest turn radius", gt(0) & le(10000));
    v.relation("turn_radius_min", turn_radius_min, turn_radius_min <= turn_radius_max,
               "<= turn_radius_max");
    v.relation("turn_radius_min", turn_radius_min,
               turn_radius_min > profile.road_half_width + profile.sidewalk_width,
               "> road_half_width + sidewalk_width");
    v("building_share", building_share, "", "probability a frontage segment is a building",
      in(0, 1));
    v("fence_share", fence_share, "", "probability a frontage segment is a fence (rest: hedge)",
      in(0, 1));
    v.relation("fence_share", fence_share, building_share + fence_share <= 1.0,
               "<= 1 - building_share");
    v("building_height_min", building_height_min, "m", "lowest building", gt(0) & le(1000));
    v("building_height_max", building_height_max, "m", "highest building", gt(0) & le(1000));
    v.relation("building_height_min", building_height_min,
               building_height_min <= building_height_max, "<= building_height_max");
    v("pole_spacing", pole_spacing, "m", "mean pole spacing per side", in(1, 100000));
    v("tree_spacing", tree_spacing, "m", "mean sidewalk tree spacing per side", in(1, 100000));
    v("parked_share", parked_share, "", "share of 30 m stretches of the right curb with parking",
      in(0, 1));
    v("moving_vehicles", moving_vehicles, "", "cars driving along the road", ge(0) & lt(60000));
  }
};

/// @brief Generates the street. Same params and seed => same scene.
LidarScene generateStreet(const StreetParams& params, uint64_t seed);

}  // namespace mapfuse::sim
