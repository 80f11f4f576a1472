#include "mapfuse/stages/simulate.hpp"

#include <chrono>

#include "mapfuse/cli/params.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/core/progress.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/geojson.hpp"
#include "mapfuse/io/json_geometry.hpp"
#include "mapfuse/io/lsm_io.hpp"
#include "mapfuse/io/output_transaction.hpp"
#include "mapfuse/io/stage_report.hpp"
#include "mapfuse/io/vector_map_io.hpp"
#include "mapfuse/sim/map_world.hpp"

namespace mapfuse::stages {
namespace {

/// The procedural world, or the Lanelet2 map's (origin: its first node unless configured).
sim::World buildWorld(const SimulateParams& P, geo::GeoOrigin& origin) {
  if (P.map.empty()) return sim::proceduralWorld(P.crowd, origin);
  return sim::loadMapWorld(P.map, P.osm_origin == "first_node", P.map_world, &origin);
}

/// The true trajectory of a drive at the given samples (mapfuse.trajectory).
nlohmann::json trajectoryJson(const sim::Drive& d, const std::vector<std::size_t>& samples,
                              const geo::GeoOrigin& origin) {
  nlohmann::json j;
  j["format"] = "mapfuse.trajectory";
  j["version"] = 1;
  j["drive_id"] = d.drive_id;
  j["vehicle_id"] = d.vehicle_id;
  j["frame"] = "enu";
  j["origin"] = io::originToJson(origin);
  j["sensor_errors"] = {{"wheel_scale_error", d.wheel_scale_error},
                        {"gyro_bias", {d.gyro_bias.x(), d.gyro_bias.y(), d.gyro_bias.z()}},
                        {"gps_initial_bias_enu", {d.gps_bias0.x(), d.gps_bias0.y()}}};
  nlohmann::json poses = nlohmann::json::array();
  for (std::size_t i = 0; i < samples.size(); ++i)
    poses.push_back({{"id", static_cast<int64_t>(i)},
                     {"stamp", d.stamps[samples[i]]},
                     {"pose", io::poseToJson(d.truth[samples[i]])}});
  j["poses"] = poses;
  return j;
}

/// Simulates every traversal (in parallel) and writes its files; returns the summed counts.
sim::CrowdStats simulateTraversals(const SimulateParams& P, const sim::Crowd& crowd,
                                   const geo::GeoOrigin& origin, const std::filesystem::path& out) {
  const int n = P.crowd.traversals;
  const std::string ext = P.format == "cbor" ? ".lsm.cbor" : ".lsm.json";
  std::vector<sim::CrowdStats> stats(n);
  std::vector<std::string> errors(n);
  Progress progress("simulate", n);
#pragma omp parallel for schedule(dynamic)
  for (int i = 0; i < n; ++i) {
    try {
      const sim::Traversal t = crowd.traversal(i, &stats[i]);
      const std::string& id = t.drive.drive_id;
      // True poses at the LSM keyframes, or at every camera frame (frames: evaluate matches).
      const auto samples = P.level == "frames" ? sim::cameraSamples(t.drive, P.crowd.drive)
                                               : t.observed.keyframe_samples;
      io::writeDocument(out / "truth" / (id + ".trajectory.json"),
                        trajectoryJson(t.drive, samples, origin));
      if (P.level == "lsm") io::writeLsm(out / "lsm" / (id + ext), t.observed.lsm);
      if (P.level == "frames") stats[i].frames = crowd.writeFrames(t, out / "frames" / id);
    } catch (const std::exception& e) {
      errors[i] = e.what();
    }
#pragma omp critical(simulate_progress)
    progress.advance();
  }
  progress.finish();
  for (const auto& e : errors)
    if (!e.empty()) throw Error("simulate: " + e);
  sim::CrowdStats total;
  for (const auto& s : stats) total.add(s);
  return total;
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
  for (const auto& [kind, e] : run.world.warnings.entries())  // what the map reader repaired
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
  const sim::World world = buildWorld(P, run.origin);
  if (world.lanes.empty()) throw InputError("simulate: the world has no drivable lanes");
  MAPFUSE_INFO("simulate: world " << world.name << ": " << world.lanes.size() << " lanes, "
                                  << world.truth.instances.size() << " true elements");
  io::writeVectorMap(out / "truth" / "vector_map.json", world.truth);
  io::writeGeoJson(out / "truth" / "vector_map.geojson", world.truth);
  run.stats = simulateTraversals(P, sim::Crowd(world, run.origin, P.crowd), run.origin, out);

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
