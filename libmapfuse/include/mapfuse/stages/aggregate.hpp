#pragma once
/// @file The `aggregate` stage (§4.3, Song et al. 2023): georeferenced or aligned LSMs (frame
/// enu, one shared origin) -> vector map in several formats plus a summary with the map size
/// in KB/km. Wires libmapfuse/aggregate; docs/aggregate.md.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mapfuse/aggregate/aggregator.hpp"
#include "mapfuse/core/lsm.hpp"
#include "mapfuse/cli/params.hpp"

namespace mapfuse::stages {

struct AggregateParams {
  // lane lines, stage 1 (buffered polygons, overlap DBSCAN)
  double buffer_width = 0.2;       ///< m
  double min_overlap_ratio = 0.3;  ///< overlap area / smaller polygon
  int lane_min_pts = 3;
  double tile_size = 10.0;    ///< m
  double station_step = 1.0;  ///< m
  // lane lines, stage 2 (linking with MinPts <= |N| <= MaxPts)
  double link_distance = 8.0;    ///< m
  double link_lateral = 1.0;     ///< m
  double link_angle_deg = 30.0;  ///< deg
  int link_min_pts = 1;
  int link_max_pts = 2;
  double min_instance_length = 3.0;  ///< m
  // vectorization
  double max_deviation = 0.08;  ///< m
  double sample_step = 0.5;     ///< m
  // discrete elements
  double min_iou = 0.2;
  double sign_radius = 1.0;       ///< m
  double point_radius = 1.0;      ///< m
  double stop_line_radius = 1.5;  ///< m
  int discrete_min_pts = 3;
  int partner_drives = 4;
  // outputs
  /// m; a power of two (1/256 m) makes every rounded coordinate exact in float32, which the
  /// CBOR writer then stores in 5 bytes instead of 9 (up to ±65 km from the origin)
  double coordinate_quantum = 0.00390625;
  double png_resolution = 0.2;  ///< m/px
  bool write_png = true;
  double road_tolerance = 10.0;  ///< m, lateral width merged when measuring road km

  template <class V>
  void visit(V& v) {
    v("buffer_width", buffer_width, "m", "stage 1: half width of the lane buffer polygons");
    v("min_overlap_ratio", min_overlap_ratio, "",
      "stage 1 eps: overlap area / smaller polygon area for neighbours");
    v("lane_min_pts", lane_min_pts, "", "stage 1 MinPts (capped by the number of drives)");
    v("tile_size", tile_size, "m", "stage 1: observations are cut at a square tiling of this size");
    v("station_step", station_step, "m", "bin length of fragment centrelines");
    v("link_distance", link_distance, "m", "stage 2 eps: longest gap between linked fragments");
    v("link_lateral", link_lateral, "m", "stage 2: largest lateral offset across a link");
    v("link_angle_deg", link_angle_deg, "deg", "stage 2: largest direction change across a link");
    v("link_min_pts", link_min_pts, "", "stage 2 MinPts");
    v("link_max_pts", link_max_pts, "", "stage 2 MaxPts (2: one follower; forks start instances)");
    v("min_instance_length", min_instance_length, "m", "shorter lane instances are dropped");
    v("max_deviation", max_deviation, "m", "largest Bezier deviation from the centreline");
    v("sample_step", sample_step, "m", "spacing of the sampled lane-line points");
    v("min_iou", min_iou, "", "arrows/crosswalks: DBSCAN eps as 1 - IoU <= 1 - min_iou");
    v("sign_radius", sign_radius, "m", "traffic signs: DBSCAN eps on 3D distance");
    v("point_radius", point_radius, "m", "poles/lights: DBSCAN eps on 3D distance");
    v("stop_line_radius", stop_line_radius, "m",
      "stop lines: DBSCAN eps on the distance of a midpoint to the other line");
    v("discrete_min_pts", discrete_min_pts, "", "discrete MinPts (capped by the number of drives)");
    v("partner_drives", partner_drives, "",
      "DBSCAN compares an observation with those of at most this many other drives (0 = all)");
    v("coordinate_quantum", coordinate_quantum, "m",
      "rounding of the CBOR map coordinates (power of two: float32 in CBOR)");
    v("png_resolution", png_resolution, "m/px", "top-down picture resolution");
    v("write_png", write_png, "", "write map.png");
    v("road_tolerance", road_tolerance, "m", "lateral width counted once when measuring road km");
  }
  /// @throws ConfigError naming the field, the value and the rule.
  void validate() const;
  /// @brief The library parameters these map to.
  aggregate::AggregatorParams toAggregator() const;
};

/// @brief Road length (km) covered by the LSM trajectories: keyframe paths sampled every metre,
/// a sample counting only when no sample of an earlier drive lies within `tolerance` metres.
double coveredRoadKm(const std::vector<Lsm>& lsms, double tolerance);

/// @brief Runs the stage: reads `inputs` (LSM files, JSON or CBOR), aggregates and writes into
/// `out_dir`: map.cbor (compact), map.json, map.geojson, map.osm, map.png, aggregate.config.json
/// and aggregate.summary.json.
/// @return the summary written.
/// @throws IoError, ParseError, InputError (frame odom, origin mismatch, no input).
nlohmann::json runAggregate(const std::vector<std::string>& inputs,
                            const std::filesystem::path& out_dir, const AggregateParams& params);

}  // namespace mapfuse::stages
