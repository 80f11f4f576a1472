#pragma once
/// @file Stage `simulate` (docs/simulate.md): crowdsourced drives over a Lanelet2 map or the
/// seeded procedural world, written as per-traversal LSMs (`--level lsm`), raw frames for
/// lsm-build (`--level frames`, docs/formats-frames.md) or ground truth only (`--level truth`),
/// always with the ground truth: the true vector map, true keyframe trajectories and truth ids.
/// The simulation itself is sim::Crowd; this stage reads the map and writes the files.
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "mapfuse/core/param.hpp"
#include "mapfuse/geo/origin.hpp"
#include "mapfuse/sim/crowd.hpp"
#include "mapfuse/sim/map_world.hpp"
#include "mapfuse/sim/world_changes.hpp"

namespace mapfuse::stages {

struct SimulateParams {
  static constexpr const char* kName = "SimulateParams";
  std::string level = "lsm";              ///< lsm | frames | truth
  std::string format = "cbor";            ///< LSM encoding: cbor | json
  std::string map;                        ///< Lanelet2 .osm / OpenDRIVE .xodr; empty = procedural
  std::string osm_origin = "first_node";  ///< first_node | config (origin_lat/lon/alt)
  double origin_lat = 49.0;               ///< deg
  double origin_lon = 8.4;                ///< deg
  double origin_alt = 110.0;              ///< m
  sim::MapWorldSettings map_world;        ///< how a Lanelet2 map becomes a world
  sim::CrowdSettings crowd;
  sim::ChangeSettings changes;  ///< true changes applied to the world before the drives

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("level", level, "", "output level", oneOf({"lsm", "frames", "truth"}));
    v("format", format, "", "LSM encoding", oneOf({"cbor", "json"}));
    v("map", map, "", "Lanelet2 .osm or OpenDRIVE .xodr map; empty = the procedural world");
    v("osm_origin", osm_origin, "",
      "ENU origin of a map (first_node: .osm first node, .xodr georeference; config: "
      "origin_lat/lon/alt)",
      oneOf({"first_node", "config"}));
    map_world.visit(v);
    v("origin_lat", origin_lat, "deg", "ENU origin latitude (procedural world, osm_origin=config)",
      in(-90, 90));
    v("origin_lon", origin_lon, "deg", "ENU origin longitude", in(-180, 180));
    v("origin_alt", origin_alt, "m", "ENU origin ellipsoidal altitude", in(-10000, 100000));
    crowd.visit(v);
    changes.visit(v);
  }
};

/// What one simulate run made (simulate.summary.json).
struct SimulateRun {
  std::string level;
  geo::GeoOrigin origin;  ///< ENU origin of the world and the outputs
  sim::WorldSummary world;
  int drives = 0, vehicles = 0;
  sim::CrowdStats stats;               ///< over all traversals
  sim::DriveParams drive;              ///< the sensor errors configured (for the expected errors)
  std::map<std::string, int> changes;  ///< true changes applied, by kind (none: empty)
  double seconds = 0.0;                ///< wall time
};

/// @brief The summary (without the wall time: simulate.summary.json is byte-identical between
/// runs of one seed).
nlohmann::json toJson(const SimulateRun& run);

/// @brief Runs the simulator and writes everything below `out_dir` atomically.
/// @throws ConfigError, IoError (missing map: exit 4), ParseError (malformed map).
SimulateRun runSimulate(const SimulateParams& params, const std::filesystem::path& out_dir);

}  // namespace mapfuse::stages
