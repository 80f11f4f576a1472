#pragma once
/// @file A simulator World from an OpenDRIVE map (docs/simulate.md "OpenDRIVE maps"): every
/// driving lane of every lane section becomes a lane in its driving direction (right lanes along
/// the reference line under right-hand traffic, left lanes against it; `rule="LHT"` swaps them),
/// its successors from the lane links, the road links and the junctions' connections (so drives
/// follow lanes through junctions); lane borders with road marks become lane lines (`broken` ->
/// dashed, double marks one line with a note), signals signs and traffic lights, objects poles
/// and crosswalks. Positions go through the header's georeference to WGS84, then to ENU.
#include <optional>

#include "mapfuse/geo/map_projection.hpp"
#include "mapfuse/geo/origin.hpp"
#include "mapfuse/io/opendrive.hpp"
#include "mapfuse/sim/world.hpp"

namespace mapfuse::sim {

/// Sizes an OpenDRIVE map may leave out.
struct OpenDriveAssumptions {
  double sign_size = 0.6;     ///< m, plate width and height when the signal has none
  double sign_bottom = 2.0;   ///< m above the road when zOffset is 0
  double light_height = 0.9;  ///< m, housing
  double light_bottom = 2.8;  ///< m above the road when zOffset is 0
  double sample_step = 0.5;   ///< m along s between polyline points
};

/// @brief The WGS84 origin of the map's own frame: the georeference at map (0, 0) (after the
/// header offset), altitude fallback.alt; a map without georeference keeps `fallback` (a local
/// frame: its x/y are ENU metres about it). @throws InputError for an unsupported georeference.
geo::GeoOrigin openDriveOrigin(const io::OdrMap& map, const geo::GeoOrigin& fallback);

/// @brief Converts a parsed OpenDRIVE map into a World in ENU of `origin`, after the content
/// checks (sim/opendrive_checks.hpp; their warnings in World::warnings). Without a georeference
/// the map's x/y are taken as ENU metres about `origin` (one warning).
/// @throws InputError for an unsupported georeference; ParseError for structural nonsense.
World worldFromOpenDrive(const io::OdrMap& map, const geo::GeoOrigin& origin,
                         const OpenDriveAssumptions& assumptions = {});

}  // namespace mapfuse::sim
