#pragma once
/// @file What a Lanelet2 export knows beyond Lanelet2's tag vocabulary (docs/formats.md "Lanelet2
/// export", "The sidecar map.osm.mapfuse.json"): per OSM element the map id it came from, a
/// pole's height, a connector's drive count. Lanelet2's validator (mapping.unknown_tags) warns
/// about any other tag, so map.osm carries none and this JSON file beside it holds them, with
/// the FNV-1a hash of the map.osm it describes: a reader applies it only to that file (an edited
/// map.osm makes it stale, and a stale sidecar is ignored, never applied to renumbered ids).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace mapfuse::io {

struct Lanelet2Map;  // io/lanelet2_osm.hpp

/// One OSM element's additions.
struct OsmSidecarEntry {
  std::string element;                ///< "node", "way" or "relation"
  int64_t id = 0;                     ///< its OSM id in map.osm
  std::optional<int64_t> mapfuse_id;  ///< the map instance it comes from
  std::optional<double> height;       ///< m, a pole's vertical extent
  int connector_drives = 0;           ///< drives that crossed this connector lanelet (0: none)
};

struct OsmSidecar {
  std::string osm_hash;  ///< FNV-1a 64 of the map.osm bytes, 16 hex digits
  std::vector<OsmSidecarEntry> entries;
};

/// @brief FNV-1a 64-bit hash of `bytes` as 16 lower-case hex digits.
std::string fnv1a64Hex(const std::string& bytes);

/// @brief The sidecar's path for an OSM file: `<path>.mapfuse.json`.
std::filesystem::path osmSidecarPath(const std::filesystem::path& osm_path);

/// @brief The sidecar as JSON text (format `mapfuse.osm_sidecar`, version 1).
std::string osmSidecarToJson(const OsmSidecar& sidecar);

/// @brief Parses a sidecar. @throws ParseError naming the file and field.
OsmSidecar parseOsmSidecar(const std::string& text, const std::string& file);

/// @brief Applies the sidecar of `osm_path` (when it exists) to `map`, parsed from `xml`, the
/// bytes of that file: its map ids and heights become `mapfuse_id` / `height` tags of the nodes
/// and ways it names (a `height` the file has stays); a sidecar whose hash is not that of `xml`
/// is not applied (map.sidecar = kStale). @throws ParseError when the sidecar is malformed.
void applyOsmSidecar(const std::filesystem::path& osm_path, const std::string& xml,
                     Lanelet2Map& map);

}  // namespace mapfuse::io
