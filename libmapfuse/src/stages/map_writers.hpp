#pragma once
/// @file The writers of a vector map in the formats the map stages (aggregate, update) write,
/// each file atomic: map.osm (Lanelet2; its lanelets' travel directions from the drives'
/// keyframe paths), map.cbor, map.json, map.geojson. The files are independent, so the caller
/// runs the writers side by side. They refer to the arguments, which must outlive them.
#include <filesystem>
#include <functional>
#include <vector>

#include "mapfuse/core/lsm.hpp"
#include "mapfuse/core/vector_map.hpp"
#include "mapfuse/io/osm_export.hpp"
#include "mapfuse/io/vector_map_io.hpp"
#include "mapfuse/lanelet/settings.hpp"

namespace mapfuse::stages {

/// @param cbor how map.cbor is written (aggregate: compact, quantized)
/// @param osm_stats filled by the map.osm writer
std::vector<std::function<void()>> vectorMapWriters(const std::filesystem::path& out_dir,
                                                    const VectorMap& map,
                                                    const std::vector<Lsm>& drives,
                                                    const lanelet::LaneletSettings& lanelet,
                                                    const io::VectorMapWriteOptions& cbor,
                                                    io::Lanelet2ExportStats* osm_stats);

}  // namespace mapfuse::stages
