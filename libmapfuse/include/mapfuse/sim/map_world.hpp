#pragma once
/// @file A simulator World read from a map file (docs/simulate.md "Worlds"): a Lanelet2 `.osm`
/// or an OpenDRIVE `.xodr` map, chosen by the file's extension, and the check that the world
/// has true markings to observe.
#include <string>

#include "mapfuse/core/param.hpp"
#include "mapfuse/geo/origin.hpp"
#include "mapfuse/sim/world.hpp"

namespace mapfuse::sim {

/// How a map file becomes a world.
struct MapWorldSettings {
  /// Accept a world without a single true marking (lane line, stop line, crosswalk or arrow read
  /// from the map): its drives observe only signs, lights and poles, if any. Without it such a
  /// world is an InputError (exit 3), e.g. a CommonRoad conversion whose ways carry no `type`.
  bool allow_no_markings = false;

  template <class V>
  void visit(V& v) {
    v("allow_no_markings", allow_no_markings, "",
      "simulate on a map world without true markings (else exit 3)");
  }
};

/// @brief Number of marking elements (lane lines, stop lines, crosswalks, arrows) of a world that
/// come from the map itself, not placed by the simulator.
int trueMarkings(const World& world);

/// @brief Reads `path` (.xodr: OpenDRIVE; anything else: Lanelet2 OSM) into a World in ENU of
/// `*origin`.
/// @param map_origin true: the map's own origin replaces `*origin`'s lat/lon (Lanelet2: the
/// first node; OpenDRIVE: the georeference's origin), keeping its altitude.
/// @throws IoError (missing file), ParseError (malformed map), InputError (no drivable lane, or
/// no true marking without settings.allow_no_markings).
World loadMapWorld(const std::string& path, bool map_origin, const MapWorldSettings& settings,
                   geo::GeoOrigin* origin);

}  // namespace mapfuse::sim
