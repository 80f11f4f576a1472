#pragma once
/// @file Lanelet2-style OSM export of a vector map (JOSM XML, version 0.6, WGS84 lat/lon):
/// lane lines as ways `type=line_thin` with `subtype=solid|dashed` (and `color=white|yellow`),
/// stop lines as ways `type=stop_line`, ground arrows as closed ways `type=arrow`, crosswalks
/// as closed ways `type=zebra_marking`, and traffic signs, traffic lights and poles as tagged
/// nodes (`type=traffic_sign|traffic_light|pole`, `height`). Node altitudes go to the `ele` tag.
/// Lanelets themselves (left/right bound relations) are not derived.
#include <filesystem>
#include <string>

#include "mapfuse/core/vector_map.hpp"

namespace mapfuse::io {

/// @brief The OSM XML document as a string (ids from 1; nodes, then ways).
std::string vectorMapToOsm(const VectorMap& map);

/// @brief Atomic write of vectorMapToOsm(). @throws IoError.
void writeOsm(const std::filesystem::path& path, const VectorMap& map);

}  // namespace mapfuse::io
