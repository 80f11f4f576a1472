#pragma once
/// @file GeoJSON export of a vector map (RFC 7946, docs/formats.md "GeoJSON export"): WGS84
/// [lon, lat, alt], at most 7 decimals for lon/lat. Lane and stop lines are LineStrings; only
/// horizontal footprints (ground arrows, crosswalks) are Polygons, closed, counter-clockwise and
/// simple after rounding (valid under GEOS); traffic signs are Points at the bottom centre of the
/// plate with `width` and `height`, lights and poles Points with `height`. Properties carry id,
/// class, attributes, size and support. QGIS and GDAL (ogrinfo) open it as is.
#include <filesystem>

#include "mapfuse/core/vector_map.hpp"
#include "mapfuse/io/json_view.hpp"

namespace mapfuse::io {

/// @brief The FeatureCollection of `map` (one Feature per instance, id = instance id).
Json vectorMapToGeoJson(const VectorMap& map);
/// @brief Atomic write of vectorMapToGeoJson(). @throws IoError.
void writeGeoJson(const std::filesystem::path& path, const VectorMap& map);

}  // namespace mapfuse::io
