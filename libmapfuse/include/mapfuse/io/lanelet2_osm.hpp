#pragma once
/// @file Lanelet2 OSM reader (docs/simulate.md "Lanelet2 maps"), with pugixml. Reads nodes
/// (lat/lon, optional `ele`), ways (line strings typed by `type` / `subtype`) and relations
/// (lanelets with `left` / `right` bounds, regulatory elements) and tagged points (`type=pole`).
/// Negative ids and missing optional tags are normal; a way without a `type` tag (CommonRoad
/// conversions write them) is read as `virtual` and counted in `untyped_ways`; way types outside
/// the Lanelet2 tagging spec and unknown relation types are kept as geometry but counted as
/// skipped. Structural faults (XML syntax, truncation, a duplicate node, way or relation id, a
/// reference to a missing node, way or relation (way nodes, every member of a lanelet or
/// regulatory element), a coordinate outside docs/formats.md "Value bounds", an id beyond
/// +-(2^63 - 2^32), a lanelet without a bound or whose left bound is its right bound) are
/// ParseErrors naming the file, the element and the field (docs/formats.md "Map content
/// checks").
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "mapfuse/geo/origin.hpp"

namespace mapfuse::io {

/// One OSM way of a Lanelet2 map (a Lanelet2 "line string").
struct Lanelet2LineString {
  int64_t id = 0;
  std::string type;     ///< `type` tag ("" when absent)
  std::string subtype;  ///< `subtype` tag ("" when absent)
  std::map<std::string, std::string> tags;
  std::vector<int64_t> node_ids;
  std::vector<geo::LatLonAlt> points;  ///< WGS84; alt = `ele` of the node, else 0
  bool known_type = false;             ///< type is one of the Lanelet2 tagging spec
  bool untyped = false;                ///< had no `type` tag and was read as `virtual`
};

/// A node carrying a `type` tag of its own (e.g. `pole`), other than the dash markers.
struct Lanelet2Point {
  int64_t id = 0;
  std::string type;
  std::map<std::string, std::string> tags;
  geo::LatLonAlt position;  ///< alt = `ele`, else 0
};

/// One lanelet relation.
struct Lanelet2Lanelet {
  int64_t id = 0;
  int64_t left = 0;     ///< way id of the left bound
  int64_t right = 0;    ///< way id of the right bound
  std::string subtype;  ///< "road", "crosswalk", ... ("" when absent)
  bool one_way = true;  ///< tag one_way (default yes, as Lanelet2's traffic rules)
  std::vector<int64_t> regulatory_elements;  ///< relation ids
};

/// A regulatory element relation (traffic light, traffic sign, right of way...).
struct Lanelet2Regulatory {
  int64_t id = 0;
  std::string subtype;
  std::vector<int64_t> refers;        ///< way ids (role "refers")
  std::vector<int64_t> ref_lines;     ///< way ids (role "ref_line", e.g. stop lines)
  std::vector<int64_t> yield;         ///< lanelet relation ids (role "yield")
  std::vector<int64_t> right_of_way;  ///< lanelet relation ids (role "right_of_way")
};

struct Lanelet2Map {
  std::string file;
  std::optional<geo::LatLonAlt> first_node;  ///< first node in file order (default origin)
  std::size_t node_count = 0;
  std::vector<Lanelet2LineString> linestrings;  ///< every way, file order
  std::vector<Lanelet2Point> points;            ///< typed nodes (not `begin`/`end`/`start`)
  int untyped_ways = 0;                         ///< ways without `type`, read as `virtual`
  std::vector<Lanelet2Lanelet> lanelets;
  std::vector<Lanelet2Regulatory> regulatory_elements;
  std::map<std::string, int> skipped_way_types;       ///< unknown way type -> count
  std::map<std::string, int> skipped_relation_types;  ///< unknown relation type -> count
  std::map<int64_t, std::size_t> way_index;           ///< way id -> index in linestrings
  std::set<int64_t> relation_ids;                     ///< every relation read, of any type
  /// The sidecar `<file>.mapfuse.json` (io/osm_sidecar.hpp) of a mapfuse export: absent,
  /// applied (its map ids and pole heights became `mapfuse_id` / `height` tags of the nodes and
  /// ways), or stale (written for another version of the file, so ignored).
  enum class Sidecar { kAbsent, kApplied, kStale } sidecar = Sidecar::kAbsent;

  /// @brief Number of line strings of a type (and subtype when not empty).
  int countWays(const std::string& type, const std::string& subtype = "") const;
  /// @brief The way with `id`; nullptr when absent.
  const Lanelet2LineString* way(int64_t id) const;
};

/// Way types of the Lanelet2 tagging spec (LinestringTagging.md: lane boundaries, barriers,
/// symbols, signs and lights); others are skipped and counted.
bool isKnownLanelet2WayType(const std::string& type);

/// @brief Parses a Lanelet2 OSM file and applies its sidecar when there is one for this very
/// file (Lanelet2Map::sidecar says which).
/// @throws IoError when unreadable; ParseError(file, element, problem) when it or its sidecar
/// is malformed.
Lanelet2Map readLanelet2Osm(const std::filesystem::path& path);

/// @brief Parses OSM XML held in memory; `file` names the source in errors.
Lanelet2Map parseLanelet2Osm(const std::string& xml, const std::string& file);

}  // namespace mapfuse::io
