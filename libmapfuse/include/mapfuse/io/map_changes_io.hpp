#pragma once
/// @file Map change files (docs/formats.md "Map changes"): format "mapfuse.map_changes",
/// version 1, ENU with an explicit origin, JSON or CBOR by extension; the change truth of
/// `simulate` (truth/changes.json) and the change report of a map update. The GeoJSON export
/// (WGS84) draws each change as the features of its states.
#include <filesystem>

#include "mapfuse/core/map_changes.hpp"
#include "mapfuse/io/json_view.hpp"

namespace mapfuse::io {

constexpr const char* kMapChangesFormat = "mapfuse.map_changes";
constexpr int kMapChangesVersion = 1;

Json mapChangesToJson(const MapChanges& changes);
/// @brief Parses and checks a change document: known kind and class, the states each kind
/// needs (and no other), point counts of the class's geometry, coordinates and heights within
/// bounds, confidence in [0, 1], each before_id and each after_id at most once.
/// @throws ParseError naming `file`, the field (e.g. "changes[3].before_id") and the problem.
MapChanges mapChangesFromJson(const Json& doc, const std::string& file);

MapChanges readMapChanges(const std::filesystem::path& path);
void writeMapChanges(const std::filesystem::path& path, const MapChanges& changes);

/// @brief FeatureCollection (RFC 7946, as io/geojson.hpp draws elements): per change one
/// feature per state it has (removed: before; added: after; others: before and after), with
/// properties change (index), state, kind, class, before_id, after_id and, when set, confidence
/// and supporting_traversals (count) with traversal_ids (comma-separated).
Json mapChangesToGeoJson(const MapChanges& changes);
void writeMapChangesGeoJson(const std::filesystem::path& path, const MapChanges& changes);

}  // namespace mapfuse::io
