#pragma once
/// @file Stage `simulate-lidar`: a seeded synthetic KITTI raw drive with LiDAR + camera ground
/// truth (docs/lidar-ground-truth.md). Writes `<out>/<date>/calib_*.txt` and
/// `<out>/<date>/<date>_drive_<drive>_sync/` with image_02, velodyne_points, oxts, timestamps,
/// `semantics_02/<frame>.prob` (network-like probabilities), `labels/<frame>.label` (true
/// SemanticKITTI labels, moving cars 252, instance ids in the upper 16 bits) and
/// `ground_truth/` (true label images, true poses), plus simulate-lidar.{config,summary}.json.
#include <cstdint>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "mapfuse/cli/params.hpp"
#include "mapfuse/sim/lidar_network_error.hpp"
#include "mapfuse/sim/lidar_scene_generator.hpp"
#include "mapfuse/sim/lidar_sensor.hpp"

namespace mapfuse::stages {

struct SimulateLidarParams {
  int64_t seed = 1;                 ///< scene and noise seed
  std::string date = "2011_09_26";  ///< KITTI date folder name (YYYY_MM_DD)
  std::string drive = "0001";       ///< drive name: <date>_drive_<drive>_sync
  int frames = 60;                  ///< number of frames
  double frame_rate = 10.0;         ///< Hz
  double ego_speed = 8.0;           ///< m/s
  double ego_start = 25.0;          ///< m, arc length of frame 0 on the road
  double velo_height = 1.73;        ///< m, Velodyne above the road
  // Street.
  double road_half_width = 5.0;       ///< m
  double sidewalk_width = 3.0;        ///< m
  double curb_height = 0.15;          ///< m
  double lane_width = 3.5;            ///< m
  double straight_min = 60.0;         ///< m
  double straight_max = 110.0;        ///< m
  double turn_radius_min = 18.0;      ///< m
  double turn_radius_max = 30.0;      ///< m
  double building_share = 0.55;       ///<
  double fence_share = 0.25;          ///<
  double building_height_min = 6.0;   ///< m
  double building_height_max = 18.0;  ///< m
  double pole_spacing = 25.0;         ///< m
  double tree_spacing = 18.0;         ///< m
  double parked_share = 0.5;          ///<
  int moving_vehicles = 6;            ///<
  // LiDAR.
  int azimuth_steps = 2150;        ///< per laser and turn
  double lidar_min_range = 2.5;    ///< m
  double lidar_max_range = 120.0;  ///< m
  double range_noise = 0.02;       ///< m
  double dropout = 0.03;           ///<
  // Camera and network errors.
  double camera_max_range = 80.0;   ///< m
  double offset_u = 1.5;            ///< px
  double offset_v = 1.0;            ///< px
  double sidewalk_as_road = 0.20;   ///<
  double road_as_sidewalk = 0.06;   ///<
  double fence_as_building = 0.25;  ///<
  double building_as_fence = 0.05;  ///<
  double confusion_scale = 120.0;   ///< px
  double blobs_per_frame = 4.0;     ///<
  double blob_radius_min = 10.0;    ///< px
  double blob_radius_max = 45.0;    ///< px
  double bleed_sigma = 2.0;         ///< px
  double confidence = 0.8;          ///<
  // Geography.
  double lat0 = 49.011212804408;  ///< deg, latitude of frame 0
  double lon0 = 8.4228850417969;  ///< deg
  double alt0 = 112.83;           ///< m
  double start_time = 43200.0;    ///< s after midnight of `date` of frame 0

  template <class V>
  void visit(V& v) {
    v("seed", seed, "", "seed of the scene and of every noise draw");
    v("date", date, "", "KITTI date folder name, YYYY_MM_DD");
    v("drive", drive, "", "drive name: <date>_drive_<drive>_sync");
    v("frames", frames, "", "number of frames");
    v("frame_rate", frame_rate, "Hz", "sensor rate");
    v("ego_speed", ego_speed, "m/s", "speed of the ego vehicle");
    v("ego_start", ego_start, "m", "arc length on the road of frame 0");
    v("velo_height", velo_height, "m", "Velodyne height above the road");
    v("road_half_width", road_half_width, "m", "centreline to curb");
    v("sidewalk_width", sidewalk_width, "m", "curb to property line");
    v("curb_height", curb_height, "m", "sidewalk height above the road");
    v("lane_width", lane_width, "m", "lane width (ego and moving cars drive on lane centres)");
    v("straight_min", straight_min, "m", "shortest of the three straights");
    v("straight_max", straight_max, "m", "longest of the three straights");
    v("turn_radius_min", turn_radius_min, "m", "smallest turn radius");
    v("turn_radius_max", turn_radius_max, "m", "largest turn radius");
    v("building_share", building_share, "", "probability a frontage segment is a building");
    v("fence_share", fence_share, "", "probability a frontage segment is a fence (rest: hedge)");
    v("building_height_min", building_height_min, "m", "lowest building");
    v("building_height_max", building_height_max, "m", "highest building");
    v("pole_spacing", pole_spacing, "m", "mean pole spacing per side");
    v("tree_spacing", tree_spacing, "m", "mean sidewalk tree spacing per side");
    v("parked_share", parked_share, "", "share of 30 m stretches of the right curb with parking");
    v("moving_vehicles", moving_vehicles, "", "cars driving along the road");
    v("azimuth_steps", azimuth_steps, "", "LiDAR rays per laser per turn (64 lasers)");
    v("lidar_min_range", lidar_min_range, "m", "closer returns are dropped");
    v("lidar_max_range", lidar_max_range, "m", "farthest return");
    v("range_noise", range_noise, "m", "standard deviation of the range");
    v("dropout", dropout, "", "probability that a return is lost");
    v("camera_max_range", camera_max_range, "m", "farther surfaces render as sky");
    v("offset_u", offset_u, "px", "horizontal calibration offset of the network labels");
    v("offset_v", offset_v, "px", "vertical calibration offset of the network labels");
    v("sidewalk_as_road", sidewalk_as_road, "", "share of sidewalk area the network calls road");
    v("road_as_sidewalk", road_as_sidewalk, "", "share of road area the network calls sidewalk");
    v("fence_as_building", fence_as_building, "", "share of fence area called building");
    v("building_as_fence", building_as_fence, "", "share of building area called fence");
    v("confusion_scale", confusion_scale, "px", "size of the confused regions");
    v("blobs_per_frame", blobs_per_frame, "", "mean number of wrong-class blobs per image");
    v("blob_radius_min", blob_radius_min, "px", "smallest blob radius");
    v("blob_radius_max", blob_radius_max, "px", "largest blob radius");
    v("bleed_sigma", bleed_sigma, "px", "Gaussian softening of class boundaries");
    v("confidence", confidence, "", "probability mass on the network's labels (rest uniform)");
    v("lat0", lat0, "deg", "latitude of frame 0");
    v("lon0", lon0, "deg", "longitude of frame 0");
    v("alt0", alt0, "m", "altitude of the road at frame 0's IMU position, plus IMU height");
    v("start_time", start_time, "s", "time of frame 0 after midnight of the date");
  }
  /// @throws ConfigError naming the field, value and rule.
  void validate() const;

  sim::StreetParams street() const;         ///< the generator's share
  sim::LidarSensorParams sensor() const;    ///< the LiDAR's share
  sim::NetworkErrorParams network() const;  ///< the error model's share
};

/// @brief Generates the drive under `out` (see file comment). Returns the summary document.
/// @throws ConfigError for invalid params; IoError when writing fails.
nlohmann::json runSimulateLidar(const std::filesystem::path& out,
                                const SimulateLidarParams& params);

}  // namespace mapfuse::stages
