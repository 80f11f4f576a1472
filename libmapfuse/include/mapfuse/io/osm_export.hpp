#pragma once
/// @file Lanelet2 export of a vector map (docs/formats.md "Lanelet2 export"): OSM XML 0.6 in
/// WGS84 as Lanelet2's own writer produces it (negative ids, no version / visible attributes,
/// altitude in the `ele` tag of every node). Lane lines are `line_thin` line strings with
/// `subtype=solid|dashed` and `color`, cut where lanelets begin and end (consecutive pieces share
/// a node); pairs of neighbouring lane lines are `type=lanelet` relations (lanelet/plan.hpp)
/// with the travel direction from the drives; stop lines are `stop_line` ways; traffic signs
/// `traffic_sign` ways along the bottom edge of the plate and traffic lights 0.3 m
/// `traffic_light` ways across the approach at the housing's bottom, both with `height`; poles
/// `type=pole` nodes (their height in the sidecar); ground arrows closed `arrow` ways; crosswalks
/// `subtype=crosswalk` lanelets bounded by two `zebra_marking` ways. Lights and signs near a stop
/// line become `traffic_light` / `traffic_sign` regulatory elements (refers = the light or sign,
/// ref_line = the stop line) referenced by the lanelets the stop line crosses; intersections
/// with stop lines and no lights get `right_of_way` or `all_way_stop` elements
/// (lanelet/right_of_way.hpp). Where drives cross
/// an unmarked stretch (an intersection) from one lanelet to another, a connector lanelet with
/// `virtual` bounds shares their end nodes. This file only writes: what is derived (lanelets,
/// directions, which stop line a light serves, right of way) comes planned by
/// lanelet::planExport (lanelet/regulatory.hpp).
#include <filesystem>
#include <string>
#include <vector>

#include "mapfuse/core/vector_map.hpp"
#include "mapfuse/io/osm_sidecar.hpp"
#include "mapfuse/lanelet/regulatory.hpp"

namespace mapfuse::io {

/// What the export derived (for the summary and the docs' figures).
struct Lanelet2ExportStats {
  int lanelets = 0;                         ///< road lanelets (both bounds)
  int lanelets_direction_known = 0;         ///< oriented by drives, a stop line or a neighbour
  int lanelets_oriented_by_neighbours = 0;  ///< ... of them by a neighbour (right-hand traffic)
  int connector_lanelets = 0;               ///< across unmarked stretches, `virtual` bounds
  int crosswalk_lanelets = 0;
  int regulatory_elements = 0;         ///< traffic_light + traffic_sign relations
  int right_of_way_elements = 0;       ///< right_of_way relations (lanelet/right_of_way.hpp)
  int all_way_stop_elements = 0;       ///< all_way_stop relations
  int lanelets_with_regulatory = 0;    ///< lanelets referring to at least one
  int unmatched_pieces = 0;            ///< piece pairs whose cuts did not line up
  int same_side_lanelets_dropped = 0;  ///< second lanelets on one side of a piece (plan.hpp)
  double lane_line_m = 0.0;            ///< total lane-line length
  double bound_m = 0.0;                ///< lane-line length that bounds at least one lanelet
  int kink_vertices_removed = 0;       ///< lane-line vertices dropped as kinks (lanelet/kinks.hpp)
  double kink_max_deviation = 0.0;     ///< m: farthest dropped vertex from the line kept
  int line_ends_joined = 0;            ///< facing lane-line ends joined (lanelet/joins.hpp)
  int one_sided_connections = 0;       ///< drive connections whose bounds met on one side
};

/// @brief The OSM XML document of `map` with the lanelets and regulatory elements of `plan`
/// (lanelet::planExport of the same map); `sidecar` receives what Lanelet2's tags cannot hold
/// (map ids, pole heights, connector drive counts: io/osm_sidecar.hpp).
std::string vectorMapToOsm(const VectorMap& map, const lanelet::LaneletExportPlan& plan,
                           Lanelet2ExportStats* stats = nullptr, OsmSidecar* sidecar = nullptr);

/// @brief Atomic write of vectorMapToOsm() to `path` and of its sidecar to osmSidecarPath(path)
/// (`map.osm.mapfuse.json`). @throws IoError.
void writeOsm(const std::filesystem::path& path, const VectorMap& map,
              const lanelet::LaneletExportPlan& plan, Lanelet2ExportStats* stats = nullptr);

}  // namespace mapfuse::io
