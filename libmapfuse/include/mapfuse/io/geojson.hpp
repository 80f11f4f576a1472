#pragma once
/// @file GeoJSON export of a vector map (RFC 7946): WGS84 [lon, lat, alt], at most 7 decimals
/// for lon/lat, polygons closed and counter-clockwise; properties carry id, class, attributes,
/// height and support. QGIS and GDAL (ogrinfo) open it as is.
#include <filesystem>

#include "mapfuse/core/vector_map.hpp"
#include "mapfuse/io/json_view.hpp"

namespace mapfuse::io {

Json vectorMapToGeoJson(const VectorMap& map);
void writeGeoJson(const std::filesystem::path& path, const VectorMap& map);

}  // namespace mapfuse::io
