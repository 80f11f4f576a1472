#include "mapfuse/stages/simulate.hpp"

#include <chrono>

#include "mapfuse/cli/params.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/io/geojson.hpp"
#include "mapfuse/io/json_geometry.hpp"
#include "mapfuse/io/map_changes_io.hpp"
#include "mapfuse/io/output_transaction.hpp"
#include "mapfuse/io/stage_report.hpp"
#include "mapfuse/io/vector_map_io.hpp"
#include "mapfuse/sim/crowd.hpp"
#include "mapfuse/sim/crowd_files.hpp"
#include "mapfuse/sim/map_world.hpp"
#include "mapfuse/sim/world_changes.hpp"

namespace mapfuse::stages {
namespace {

/// The procedural world, or the Lanelet2 map's (origin: its first node unless configured).
sim::World buildWorld(const SimulateParams& P, geo::GeoOrigin& origin) {
  if (P.map.empty()) return sim::proceduralWorld(P.crowd, origin);
  return sim::loadMapWorld(P.map, P.osm_origin == "first_node", P.map_world, &origin);
}

}  // namespace

nlohmann::json toJson(const SimulateRun& run) {
  const sim::DriveStatistics& d = run.stats.drives;
  nlohmann::json summary = {{"km_driven", d.km},
                            {"gps_fixes", d.gps_fixes},
                            {"gps_outliers_injected", d.gps_outliers},
                            {"gps_error_rms_m", d.gpsErrorRms()},
                            {"gps_error_rms_expected_m", d.gpsErrorRmsExpected(run.drive)},
                            {"odometry_drift_windows", d.drift_windows},
                            {"odometry_drift_per_100m_rms_m", d.driftRms()},
                            {"odometry_drift_per_100m_expected_m", d.driftRmsExpected()},
                            {"world", run.world.name},
                            {"level", run.level},
                            {"origin", io::originToJson(run.origin)},
                            {"drives", run.drives},
                            {"vehicles", run.vehicles},
                            {"lanes", run.world.lanes},
                            {"lane_km", run.world.lane_km},
                            {"elements", run.world.elements},
                            {"elements_by_class", run.world.elements_by_class},
                            {"lane_line_km", run.world.lane_line_km},
                            {"world_stats", run.world.stats},
                            {"observations", run.stats.observations.elements},
                            {"false_positives_injected", run.stats.observations.false_positives},
                            {"missed_detections", run.stats.observations.missed},
                            {"partial_stop_lines", run.stats.observations.partial_stop_lines}};
  if (!run.changes.empty()) summary["changes"] = run.changes;  // true changes by kind
  for (const auto& [kind, e] : run.world.warnings.entries())   // what the map reader repaired
    summary["input_warnings"][kind] = {{"count", e.count}, {"first", e.first}};
  if (run.level == "frames") {
    summary["frames"] = run.stats.frames.frames;
    summary["frame_ground_observations"] = run.stats.frames.ground_observations;
    summary["frame_aerial_observations"] = run.stats.frames.aerial_observations;
  }
  return summary;
}

SimulateRun runSimulate(const SimulateParams& P, const std::filesystem::path& out) {
  validateParams(P);
  io::OutputTransaction outputs(out);  // locked and writable before the work
  const auto t0 = std::chrono::steady_clock::now();
  SimulateRun run;
  run.origin = {P.origin_lat, P.origin_lon, P.origin_alt};
  sim::World world = buildWorld(P, run.origin);
  if (world.lanes.empty()) throw InputError("simulate: the world has no drivable lanes");
  // Before any drive, near the routes the drives will take (change_route_distance).
  const MapChanges changes =
      sim::applyWorldChanges(world, P.changes, sim::crowdRoutes(world, P.crowd));
  for (const auto& c : changes.changes) ++run.changes[changeKindName(c.kind)];
  MAPFUSE_INFO("simulate: world " << world.name << ": " << world.lanes.size() << " lanes, "
                                  << world.truth.instances.size() << " true elements");
  io::writeVectorMap(out / "truth" / "vector_map.json", world.truth);
  io::writeGeoJson(out / "truth" / "vector_map.geojson", world.truth);
  if (P.changes.total() > 0) {
    io::writeMapChanges(out / "truth" / "changes.json", changes);
    io::writeMapChangesGeoJson(out / "truth" / "changes.geojson", changes);
  }
  run.stats = sim::writeCrowdTraversals(sim::Crowd(world, run.origin, P.crowd), P.crowd,
                                        {P.level, P.format}, run.origin, out);

  run.level = P.level;
  run.world = sim::summarize(world);
  run.drives = P.crowd.traversals;
  run.vehicles = P.crowd.vehicles;
  run.drive = P.crowd.drive;
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  io::writeResolvedConfig(out, "simulate", paramsToJson(P));
  io::writeSummary(out, "simulate", toJson(run));
  outputs.commit();
  return run;
}

}  // namespace mapfuse::stages
