#pragma once
/// @file Stage `simulate` (docs/simulate.md): crowdsourced drives over a Lanelet2 map or the
/// seeded procedural world, written as per-traversal LSMs (`--level lsm`), raw frames for
/// lsm-build (`--level frames`, docs/formats-frames.md) or ground truth only (`--level truth`),
/// always with the ground truth: the true vector map, true keyframe trajectories and truth ids.
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "mapfuse/cli/params.hpp"
#include "mapfuse/sim/drive.hpp"
#include "mapfuse/sim/frames_writer.hpp"
#include "mapfuse/sim/lsm_observer.hpp"
#include "mapfuse/sim/map_world.hpp"
#include "mapfuse/sim/procedural_world.hpp"
#include "mapfuse/sim/sim_camera.hpp"

namespace mapfuse::stages {

struct SimulateParams {
  uint64_t seed = 42;                     ///< every random draw derives from it
  std::string level = "lsm";              ///< lsm | frames | truth
  std::string format = "cbor";            ///< LSM encoding: cbor | json
  std::string map;                        ///< Lanelet2 .osm / OpenDRIVE .xodr; empty = procedural
  std::string osm_origin = "first_node";  ///< first_node | config (origin_lat/lon/alt)
  double origin_lat = 49.0;               ///< deg
  double origin_lon = 8.4;                ///< deg
  double origin_alt = 110.0;              ///< m
  int traversals = 20;
  int vehicles = 4;
  int routes = 4;                ///< distinct routes; traversal i drives route i % routes
  double route_length = 1500.0;  ///< m
  sim::ProceduralParams world;
  sim::MapWorldSettings map_world;
  sim::DriveParams drive;
  sim::CameraParams camera;
  sim::ObservationParams obs;
  sim::FramesParams frames;

  template <class V>
  void visit(V& v) {
    v("seed", seed, "", "random seed (same seed, same bytes)");
    v("level", level, "", "output level: lsm | frames | truth");
    v("format", format, "", "LSM encoding: cbor | json");
    v("map", map, "", "Lanelet2 .osm or OpenDRIVE .xodr map; empty = the procedural world");
    v("osm_origin", osm_origin, "",
      "ENU origin of a map: first_node (.osm: first node, .xodr: georeference) | config");
    map_world.visit(v);
    v("origin_lat", origin_lat, "deg", "ENU origin latitude (procedural world, osm_origin=config)");
    v("origin_lon", origin_lon, "deg", "ENU origin longitude");
    v("origin_alt", origin_alt, "m", "ENU origin ellipsoidal altitude");
    v("traversals", traversals, "", "number of traversals (drives)");
    v("vehicles", vehicles, "", "number of vehicles; traversal i uses vehicle i % vehicles");
    v("routes", routes, "", "distinct routes; traversal i drives route i % routes");
    v("route_length", route_length, "m", "target length of a route");
    v("world_grid_size", world.grid_size, "", "procedural: intersections per side");
    v("world_block_length", world.block_length, "m", "procedural: intersection spacing");
    v("world_jitter", world.jitter, "m", "procedural: random shift of intersections");
    v("world_curve_amplitude", world.curve_amplitude, "m", "procedural: max road bulge");
    v("world_lane_width", world.lane_width, "m", "procedural: lane width");
    v("world_max_lanes_per_direction", world.max_lanes_per_direction, "",
      "procedural: lanes per direction in [1, this]");
    v("world_intersection_radius", world.intersection_radius, "m",
      "procedural: centre to stop line");
    v("world_traffic_light_fraction", world.traffic_light_fraction, "",
      "procedural: share of intersections with lights");
    v("world_crosswalk_probability", world.crosswalk_probability, "",
      "procedural: crosswalk per arm without lights");
    v("world_pole_spacing", world.pole_spacing, "m", "procedural: street-lamp spacing");
    v("speed_min", drive.speed_min, "m/s", "per-traversal speed, lower bound");
    v("speed_max", drive.speed_max, "m/s", "per-traversal speed, upper bound");
    v("lateral_offset_sigma", drive.lateral_offset_sigma, "m",
      "per-traversal offset from the lane centre");
    v("imu_rate", drive.imu_rate, "Hz", "IMU rate (simulation step)");
    v("wheel_rate", drive.wheel_rate, "Hz", "wheel odometry rate");
    v("gps_rate", drive.gps_rate, "Hz", "GPS fix rate");
    v("camera_rate", drive.camera_rate, "Hz", "camera frame rate");
    v("gps_bias_min", drive.gps_bias_min, "m", "initial horizontal GPS bias magnitude, min");
    v("gps_bias_max", drive.gps_bias_max, "m", "initial horizontal GPS bias magnitude, max");
    v("gps_bias_walk", drive.gps_bias_walk, "m/sqrt(s)", "random walk of the GPS bias per axis");
    v("gps_white_sigma", drive.gps_white_sigma, "m", "GPS horizontal white noise per axis");
    v("gps_vertical_sigma", drive.gps_vertical_sigma, "m", "GPS vertical white noise");
    v("gps_outlier_probability", drive.gps_outlier_probability, "",
      "multipath outlier probability per fix");
    v("gps_outlier_min", drive.gps_outlier_min, "m", "multipath outlier magnitude, min");
    v("gps_outlier_max", drive.gps_outlier_max, "m", "multipath outlier magnitude, max");
    v("gps_reported_sigma_h", drive.gps_reported_sigma_h, "m",
      "horizontal sigma reported in fixes");
    v("gps_reported_sigma_v", drive.gps_reported_sigma_v, "m", "vertical sigma reported in fixes");
    v("wheel_scale_sigma", drive.wheel_scale_sigma, "", "per-traversal wheel scale error, 1-sigma");
    v("wheel_speed_noise", drive.wheel_speed_noise, "m/s", "wheel speed white noise");
    v("gyro_bias_sigma", drive.gyro_bias_sigma, "rad/s", "per-traversal gyro bias per axis");
    v("gyro_noise_density", drive.gyro_noise_density, "rad/s/sqrt(Hz)", "gyro white noise density");
    v("accel_noise", drive.accel_noise, "m/s^2", "accelerometer white noise per sample");
    v("attitude_noise", drive.attitude_noise, "rad", "levelled roll/pitch noise of the odometry");
    v("pitch_amplitude", drive.pitch_amplitude, "rad", "body pitch oscillation amplitude");
    v("pitch_frequency", drive.pitch_frequency, "Hz", "body pitch oscillation frequency");
    v("roll_amplitude", drive.roll_amplitude, "rad", "body roll oscillation amplitude");
    v("roll_frequency", drive.roll_frequency, "Hz", "body roll oscillation frequency");
    v("camera_width", camera.width, "px", "image width");
    v("camera_height", camera.height, "px", "image height");
    v("camera_fx", camera.fx, "px", "focal length x");
    v("camera_fy", camera.fy, "px", "focal length y");
    v("camera_cx", camera.cx, "px", "principal point x");
    v("camera_cy", camera.cy, "px", "principal point y");
    v("camera_x", camera.x, "m", "camera position in the body frame, forward");
    v("camera_y", camera.y, "m", "camera position in the body frame, left");
    v("camera_z", camera.z, "m", "camera height above the road");
    v("camera_pitch", camera.pitch, "rad", "downward pitch of the optical axis");
    v("camera_min_range", camera.min_range, "m", "closest ground point used");
    v("camera_max_range", camera.max_range, "m", "farthest element observed");
    v("keyframe_spacing", obs.keyframe_spacing, "m", "odometry distance between keyframes");
    v("point_spacing", obs.point_spacing, "m", "lane-line point spacing in LSMs");
    v("lateral_range", obs.lateral_range, "m", "max |y| of observed elements");
    v("aerial_window_offset", obs.aerial_window_offset, "m",
      "aerial elements are anchored this much further ahead");
    v("ground_edge_margin_px", obs.ground_edge_margin_px, "px",
      "ground points beside the road are observed where the image first holds them with this "
      "margin (0: fixed window at camera_min_range)");
    v("ground_sigma_base", obs.ground_sigma_base, "m", "ground point noise floor");
    v("ground_sigma_range_quad", obs.ground_sigma_range_quad, "1/m",
      "along-ray ground sigma k r^2");
    v("ground_sigma_angular", obs.ground_sigma_angular, "rad", "across-ray sigma k r");
    v("aerial_sigma_base", obs.aerial_sigma_base, "m", "triangulated point noise floor");
    v("aerial_sigma_range_quad", obs.aerial_sigma_range_quad, "1/m", "aerial depth sigma k r^2");
    v("correlated_fraction", obs.correlated_fraction, "",
      "share of noise variance common to an element");
    v("miss_probability", obs.miss_probability, "", "missed detection probability per element");
    v("false_positives_per_km", obs.false_positives_per_km, "1/km", "spurious elements per km");
    v("frames_pixel_sigma", frames.pixel_sigma, "px", "pixel noise of frame observations");
    v("frames_masks", frames.masks, "", "write per-frame PNG masks");
  }
  /// @throws ConfigError naming the field, value and rule.
  void validate() const;
};

/// Result of a run (also written as simulate.summary.json).
struct SimulateResult {
  nlohmann::json summary;
};

/// @brief Runs the simulator and writes everything below `out_dir` atomically.
/// @throws ConfigError, IoError (missing map: exit 4), ParseError (malformed map).
SimulateResult runSimulate(const SimulateParams& params, const std::filesystem::path& out_dir);

}  // namespace mapfuse::stages
