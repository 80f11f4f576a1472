#pragma once
// Shared by sim/opendrive_world.cpp (lanes, routing) and sim/opendrive_elements.cpp (markings,
// signals, objects): the roads' geometry and the map -> ENU transform.
#include <memory>
#include <optional>
#include <vector>

#include "mapfuse/geo/map_projection.hpp"
#include "mapfuse/geo/origin.hpp"
#include "mapfuse/io/opendrive.hpp"
#include "mapfuse/sim/opendrive_world.hpp"
#include "mapfuse/sim/world.hpp"
#include "opendrive_geometry.hpp"

namespace mapfuse::sim::detail {

struct OdrContext {
  const io::OdrMap& map;
  OpenDriveAssumptions assumptions;
  std::vector<std::unique_ptr<RoadGeometry>> roads;  ///< parallel to map.roads
  std::optional<geo::MapProjection> projection;      ///< none: map x/y are ENU metres
  geo::EnuConverter enu;

  OdrContext(const io::OdrMap& m, const geo::GeoOrigin& origin, const OpenDriveAssumptions& a);
  /// Map metres (before the header offset) -> ENU of the world's origin.
  Eigen::Vector3d toEnu(const Eigen::Vector3d& map_xyz) const;
  /// s samples of [s0, s1] at most assumptions.sample_step apart, both ends included.
  std::vector<double> samples(double s0, double s1) const;
};

/// Adds lane lines (road marks), signs, lights, poles, crosswalks and stop lines to world.truth
/// and their counts to world.stats.
void addOpenDriveElements(const OdrContext& ctx, World& world);

}  // namespace mapfuse::sim::detail
