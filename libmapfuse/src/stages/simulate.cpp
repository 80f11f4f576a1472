// Stage `simulate`: wires world -> routes -> drives -> LSMs / frames -> ground truth + summary.
#include "mapfuse/stages/simulate.hpp"

#include <chrono>
#include <filesystem>
#include <map>

#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/core/progress.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/geojson.hpp"
#include "mapfuse/io/json_geometry.hpp"
#include "mapfuse/io/lsm_io.hpp"
#include "mapfuse/io/stage_report.hpp"
#include "mapfuse/io/vector_map_io.hpp"
#include "mapfuse/stages/simulate_stats.hpp"

namespace mapfuse::stages {

namespace {
constexpr const char* kStage = "Simulate";

std::string driveId(int vehicle, int traversal) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "veh%02d_trav%03d", vehicle, traversal);
  return buf;
}

/// Indices of the IMU-rate samples at which the camera fires (as the frames writer picks them).
std::vector<std::size_t> cameraSamples(const sim::Drive& d, const sim::DriveParams& DP) {
  const std::size_t every = sim::cameraStride(DP);
  std::vector<std::size_t> samples;
  for (std::size_t k = 0; k < d.stamps.size(); k += every) samples.push_back(k);
  return samples;
}

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
}  // namespace

void SimulateParams::validate() const {
  requireParam(level == "lsm" || level == "frames" || level == "truth", kStage, "level", level,
               "one of lsm, frames, truth");
  requireParam(format == "cbor" || format == "json", kStage, "format", format, "cbor or json");
  requireParam(osm_origin == "first_node" || osm_origin == "config", kStage, "osm_origin",
               osm_origin, "first_node or config");
  requireParam(std::abs(origin_lat) <= 90.0, kStage, "origin_lat", origin_lat, "within [-90, 90]");
  requireParam(std::abs(origin_lon) <= 180.0, kStage, "origin_lon", origin_lon,
               "within [-180, 180]");
  requireParam(traversals >= 1, kStage, "traversals", traversals, ">= 1");
  requireParam(vehicles >= 1, kStage, "vehicles", vehicles, ">= 1");
  requireParam(routes >= 1, kStage, "routes", routes, ">= 1");
  requireParam(route_length >= 50.0, kStage, "route_length", route_length, ">= 50 m");
  requireParam(world.grid_size >= 2, kStage, "world_grid_size", world.grid_size, ">= 2");
  requireParam(world.max_lanes_per_direction >= 1 && world.max_lanes_per_direction <= 4, kStage,
               "world_max_lanes_per_direction", world.max_lanes_per_direction, "within [1, 4]");
  requireParam(world.lane_width > 2.0, kStage, "world_lane_width", world.lane_width, "> 2 m");
  requireParam(world.pole_spacing > 5.0, kStage, "world_pole_spacing", world.pole_spacing, "> 5 m");
  requireParam(drive.speed_min > 0.5 && drive.speed_max >= drive.speed_min, kStage, "speed_max",
               drive.speed_max, ">= speed_min > 0.5 m/s");
  requireParam(drive.gps_bias_max >= drive.gps_bias_min && drive.gps_bias_min >= 0.0, kStage,
               "gps_bias_max", drive.gps_bias_max, ">= gps_bias_min >= 0");
  requireParam(drive.gps_outlier_max >= drive.gps_outlier_min, kStage, "gps_outlier_max",
               drive.gps_outlier_max, ">= gps_outlier_min");
  requireParam(drive.gps_outlier_probability >= 0.0 && drive.gps_outlier_probability <= 1.0, kStage,
               "gps_outlier_probability", drive.gps_outlier_probability, "within [0, 1]");
  for (const auto& [name, rate] : {std::pair<const char*, double>{"wheel_rate", drive.wheel_rate},
                                   {"gps_rate", drive.gps_rate},
                                   {"camera_rate", drive.camera_rate}}) {
    const double ratio = drive.imu_rate / rate;
    requireParam(rate > 0.0 && rate <= drive.imu_rate && std::abs(ratio - std::round(ratio)) < 1e-9,
                 kStage, name, rate, "> 0 and divides imu_rate");
  }
  requireParam(camera.width > 0 && camera.height > 0, kStage, "camera_width", camera.width,
               "image size > 0");
  requireParam(camera.fx > 0 && camera.fy > 0, kStage, "camera_fx", camera.fx, "> 0");
  requireParam(camera.z > 0.3, kStage, "camera_z", camera.z, "> 0.3 m");
  requireParam(camera.max_range > camera.min_range && camera.min_range > 0.0, kStage,
               "camera_max_range", camera.max_range, "> camera_min_range > 0");
  requireParam(obs.keyframe_spacing >= 1.0, kStage, "keyframe_spacing", obs.keyframe_spacing,
               ">= 1 m");
  requireParam(obs.point_spacing >= 0.1, kStage, "point_spacing", obs.point_spacing, ">= 0.1 m");
  requireParam(obs.correlated_fraction >= 0.0 && obs.correlated_fraction <= 1.0, kStage,
               "correlated_fraction", obs.correlated_fraction, "within [0, 1]");
  requireParam(obs.miss_probability >= 0.0 && obs.miss_probability < 1.0, kStage,
               "miss_probability", obs.miss_probability, "within [0, 1)");
  requireParam(obs.false_positives_per_km >= 0.0, kStage, "false_positives_per_km",
               obs.false_positives_per_km, ">= 0");
  requireParam(frames.pixel_sigma >= 0.0, kStage, "frames_pixel_sigma", frames.pixel_sigma, ">= 0");
}

SimulateResult runSimulate(const SimulateParams& P, const std::filesystem::path& out) {
  P.validate();
  const auto t0 = std::chrono::steady_clock::now();
  // World.
  sim::World world;
  geo::GeoOrigin origin{P.origin_lat, P.origin_lon, P.origin_alt};
  if (P.map.empty()) {
    world = sim::buildProceduralWorld(P.world, origin, sim::deriveSeed(P.seed, 1000001));
  } else {
    world = sim::loadMapWorld(P.map, P.osm_origin == "first_node", P.map_world, &origin);
  }
  if (world.lanes.empty()) throw InputError("simulate: the world has no drivable lanes");
  MAPFUSE_INFO("simulate: world " << world.name << ": " << world.lanes.size() << " lanes, "
                                  << world.truth.instances.size() << " true elements");
  // Ground truth.
  io::writeVectorMap(out / "truth" / "vector_map.json", world.truth);
  io::writeGeoJson(out / "truth" / "vector_map.geojson", world.truth);
  // Routes and traversals (each traversal has its own seeds: order-independent, deterministic).
  const auto routes =
      sim::planRoutes(world, P.routes, P.route_length, sim::deriveSeed(P.seed, 1000002));
  const sim::PieceIndex index(world, P.obs.point_spacing);
  const sim::SimCamera camera(P.camera);
  const geo::EnuConverter enu(origin);
  const std::string ext = P.format == "cbor" ? ".lsm.cbor" : ".lsm.json";
  std::vector<DriveStatistics> stats(P.traversals);
  std::vector<sim::ObservationStats> obs_stats(P.traversals);
  std::vector<sim::FramesStats> frame_stats(P.traversals);
  std::vector<std::string> errors(P.traversals);
  Progress progress("simulate", P.traversals);
#pragma omp parallel for schedule(dynamic)
  for (int i = 0; i < P.traversals; ++i) {
    try {
      const uint64_t s = sim::deriveSeed(P.seed, static_cast<uint64_t>(i));
      sim::Drive d =
          sim::simulateDrive(routes[i % routes.size()], P.drive, enu, sim::deriveSeed(s, 1));
      d.vehicle_id = driveId(i % P.vehicles, 0).substr(0, 5);
      d.drive_id = driveId(i % P.vehicles, i);
      sim::ObservedDrive od =
          sim::observeLsm(world, index, d, camera, P.obs, P.drive, sim::deriveSeed(s, 2));
      stats[i].add(d, od.keyframe_samples, P.drive);
      obs_stats[i] = od.stats;
      // The true trajectory at the LSM keyframes, or at every camera frame for raw frames
      // (lsm-build then chooses its own keyframes; evaluate matches them by stamp).
      io::writeDocument(
          out / "truth" / (d.drive_id + ".trajectory.json"),
          trajectoryJson(d, P.level == "frames" ? cameraSamples(d, P.drive) : od.keyframe_samples,
                         origin));
      if (P.level == "lsm") io::writeLsm(out / "lsm" / (d.drive_id + ext), od.lsm);
      if (P.level == "frames")
        frame_stats[i] = sim::writeFramesDrive(out / "frames" / d.drive_id, world, index, d, camera,
                                               P.drive, P.frames, sim::deriveSeed(s, 3));
    } catch (const std::exception& e) {
      errors[i] = e.what();
    }
#pragma omp critical(simulate_progress)
    progress.advance();
  }
  progress.finish();
  for (const auto& e : errors)
    if (!e.empty()) throw Error("simulate: " + e);
  // Summary.
  DriveStatistics total;
  sim::ObservationStats obs_total;
  sim::FramesStats frames_total;
  for (int i = 0; i < P.traversals; ++i) {
    const auto& s = stats[i];
    total.km += s.km;
    total.gps_fixes += s.gps_fixes;
    total.gps_outliers += s.gps_outliers;
    total.gps_inliers += s.gps_inliers;
    total.gps_sq_sum += s.gps_sq_sum;
    total.gps_stamp_sum += s.gps_stamp_sum;
    total.drift_windows += s.drift_windows;
    total.drift_sq_sum += s.drift_sq_sum;
    total.drift_expected_sq_sum += s.drift_expected_sq_sum;
    obs_total.elements += obs_stats[i].elements;
    obs_total.false_positives += obs_stats[i].false_positives;
    obs_total.missed += obs_stats[i].missed;
    frames_total.frames += frame_stats[i].frames;
    frames_total.ground_observations += frame_stats[i].ground_observations;
    frames_total.aerial_observations += frame_stats[i].aerial_observations;
  }
  nlohmann::json summary = total.toJson(P.drive);
  summary["world"] = world.name;
  summary["level"] = P.level;
  summary["origin"] = io::originToJson(origin);
  summary["drives"] = P.traversals;
  summary["vehicles"] = P.vehicles;
  summary["lanes"] = world.lanes.size();
  summary["lane_km"] = world.laneLength() / 1000.0;
  std::map<std::string, int> by_class;
  for (const auto& m : world.truth.instances) ++by_class[crowdClassName(m.cls)];
  summary["elements"] = world.truth.instances.size();
  summary["elements_by_class"] = by_class;
  summary["lane_line_km"] = totalLineLength(world.truth, CrowdClass::kLaneLine) / 1000.0;
  summary["world_stats"] = world.stats;
  summary["observations"] = obs_total.elements;
  summary["false_positives_injected"] = obs_total.false_positives;
  summary["missed_detections"] = obs_total.missed;
  if (P.level == "frames") {
    summary["frames"] = frames_total.frames;
    summary["frame_ground_observations"] = frames_total.ground_observations;
    summary["frame_aerial_observations"] = frames_total.aerial_observations;
  }
  summary["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  nlohmann::json config = paramsToJson(P);
  io::writeResolvedConfig(out, "simulate", config);
  nlohmann::json written = summary;
  written.erase("seconds");  // keep the summary byte-identical between runs
  io::writeSummary(out, "simulate", written);
  return {summary};
}

}  // namespace mapfuse::stages
