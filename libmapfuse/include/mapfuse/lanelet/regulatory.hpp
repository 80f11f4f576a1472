#pragma once
/// @file What a Lanelet2 export of a vector map says beyond its lane lines (docs/formats.md
/// "Lanelet2 export"): the lanelets every stop line crosses and its approach direction; the stop
/// line (or, without one, the nearest lanelet) each traffic light and sign serves, and the
/// direction across the approach that a light's line string takes; the right-of-way rules of the
/// intersections (lanelet/right_of_way.hpp). io's OSM writer writes exactly this plan.
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "mapfuse/core/vector_map.hpp"
#include "mapfuse/lanelet/plan.hpp"
#include "mapfuse/lanelet/right_of_way.hpp"
#include "mapfuse/lanelet/settings.hpp"

namespace mapfuse::lanelet {

/// A stop line of the map and the lanelets it crosses.
struct StopLineLink {
  std::size_t instance = 0;                            ///< index in VectorMap::instances
  Eigen::Vector3d mid = Eigen::Vector3d::Zero();       ///< middle of its end points (ENU, m)
  std::vector<std::size_t> lanelets;                   ///< plan lanelets it crosses, ascending
  Eigen::Vector2d approach = Eigen::Vector2d::Zero();  ///< unit travel direction, or zero
};

/// A traffic light or sign and what it regulates.
struct DeviceLink {
  std::size_t instance = 0;  ///< index in VectorMap::instances (map order)
  long stop = -1;            ///< index in LaneletExportPlan::stop_lines, -1: none in reach
  long lanelet = -1;         ///< without a stop line: the nearest lanelet, -1: none in reach
  Eigen::Vector2d across = Eigen::Vector2d(1, 0);  ///< lights: unit xy across the approach
};

/// Everything the OSM writer needs besides the map.
struct LaneletExportPlan {
  LaneletPlan lanes;
  std::vector<StopLineLink> stop_lines;  ///< every stop line, in map order
  std::vector<DeviceLink> devices;       ///< every traffic light and sign, in map order
  std::vector<RightOfWayRule> rules;     ///< yield_stop indexes stop_lines
};

/// @brief Plans the Lanelet2 export of `map`: lanelets (planLanelets), the stop lines, lights
/// and signs tied to them, and right of way (deriveRightOfWay). `drives`: ENU paths in the map's
/// frame, giving travel directions.
LaneletExportPlan planExport(const VectorMap& map, const std::vector<DrivePath>& drives,
                             const LaneletSettings& settings = {});

}  // namespace mapfuse::lanelet
