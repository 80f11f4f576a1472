#pragma once
/// @file The `aggregate` stage (§4.3, Song et al. 2023): reads georeferenced or aligned LSMs
/// (frame enu, one shared origin), runs aggregate::aggregateObservations, writes the vector map
/// in several formats and a summary with the map size in KB/km (docs/aggregate.md).
#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mapfuse/aggregate/aggregator.hpp"
#include "mapfuse/aggregate/road_length.hpp"
#include "mapfuse/io/osm_export.hpp"
#include "mapfuse/lanelet/settings.hpp"

namespace mapfuse::stages {

struct AggregateParams {
  static constexpr const char* kName = "AggregateParams";
  aggregate::AggregatorParams aggregator;
  /// m; a power of two (1/256 m) makes every rounded coordinate exact in float32, which the
  /// CBOR writer then stores in 5 bytes instead of 9 (up to ±65 km from the origin)
  double coordinate_quantum = 0.00390625;
  double png_resolution = 0.2;  ///< m/px
  bool write_png = true;
  aggregate::RoadLengthSettings road;
  lanelet::LaneletSettings lanelet;  ///< map.osm's lanelet inference (docs/formats.md)

  template <class V>
  void visit(V& v) {
    using namespace param;
    aggregator.visit(v);
    // coordinates are written as integer multiples of the quantum (int64)
    v("coordinate_quantum", coordinate_quantum, "m",
      "rounding of the CBOR map coordinates (power of two: float32 in CBOR)", in(0, 1));
    v.relation("coordinate_quantum", coordinate_quantum,
               coordinate_quantum == 0 || coordinate_quantum >= 1e-6, "is 0 or >= 1e-6");
    v("png_resolution", png_resolution, "m/px", "top-down picture resolution", gt(0) & le(100));
    v("write_png", write_png, "", "write map.png");
    road.visit(v);
    lanelet.visit(v);
  }
};

/// What one aggregate run did.
struct AggregateRun {
  std::string method;            ///< the aggregation method (dbscan_bezier, grid_vote)
  std::size_t drives = 0;        ///< input LSMs
  std::size_t observations = 0;  ///< their elements
  std::size_t instances = 0;     ///< map instances
  aggregate::AggregatorStats stats;
  double max_deviation_limit = 0;  ///< m, the Bezier fit's bound (max_deviation)
  double cbor_kb = 0;              ///< size of map.cbor
  double road_km = 0;              ///< road covered by the drives (aggregate::coveredRoadKm)
  double lane_line_km = 0;         ///< length of the map's lane lines
  double seconds_read = 0, seconds_aggregate = 0, seconds_write = 0;
  io::Lanelet2ExportStats lanelet2;  ///< what map.osm's Lanelet2 export derived
};

/// @brief The summary aggregate.summary.json holds (map size in KB/km against the paper's
/// 20 KB/km target, per-class counts, lane instantiation and vectorization figures; with
/// method grid_vote the grid's figures).
nlohmann::json toJson(const AggregateRun& run);

/// @brief Runs the stage: reads `inputs` (LSM files, JSON or CBOR), aggregates and writes into
/// `out_dir`: map.cbor (compact), map.json, map.geojson, map.osm (with its sidecar
/// map.osm.mapfuse.json), map.png, aggregate.config.json and aggregate.summary.json.
/// @throws ConfigError (parameters), IoError, ParseError, InputError (frame odom, origin
/// mismatch, no input).
AggregateRun runAggregate(const std::vector<std::string>& inputs,
                          const std::filesystem::path& out_dir, const AggregateParams& params);

}  // namespace mapfuse::stages
