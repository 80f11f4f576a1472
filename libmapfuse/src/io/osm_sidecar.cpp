#include "mapfuse/io/osm_sidecar.hpp"

#include <cstdio>
#include <nlohmann/json.hpp>
#include <unordered_map>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/bounds.hpp"
#include "mapfuse/io/json_view.hpp"
#include "mapfuse/io/lanelet2_osm.hpp"

namespace mapfuse::io {

namespace {
constexpr const char* kFormat = "mapfuse.osm_sidecar";
constexpr int kVersion = 1;
constexpr int kMaxDrives = 1000000000;  // a count of drives, far beyond any batch
}  // namespace

std::string fnv1a64Hex(const std::string& bytes) {
  uint64_t h = 14695981039346656037ULL;  // FNV-1a 64 offset basis and prime
  for (const unsigned char c : bytes) h = (h ^ c) * 1099511628211ULL;
  char buf[17];
  std::snprintf(buf, sizeof(buf), "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

std::filesystem::path osmSidecarPath(const std::filesystem::path& osm_path) {
  return osm_path.string() + ".mapfuse.json";
}

std::string osmSidecarToJson(const OsmSidecar& sidecar) {
  const Json head = {{"format", kFormat}, {"version", kVersion}, {"osm_fnv1a64", sidecar.osm_hash}};
  std::string out = head.dump();
  out.pop_back();  // one element per line: readable, and diffs stay small
  out += ",\"elements\":[";
  for (std::size_t k = 0; k < sidecar.entries.size(); ++k) {
    const auto& e = sidecar.entries[k];
    Json j = {{"element", e.element}, {"id", e.id}};
    if (e.mapfuse_id) j["mapfuse_id"] = *e.mapfuse_id;
    if (e.height) j["height"] = *e.height;
    if (e.connector_drives > 0) j["connector_drives"] = e.connector_drives;
    out += (k ? ",\n " : "\n ") + j.dump();
  }
  return out + "\n]}\n";
}

OsmSidecar parseOsmSidecar(const std::string& text, const std::string& file) {
  Json doc;
  try {
    doc = Json::parse(text);
  } catch (const Json::parse_error& e) {
    throw ParseError(file, "", std::string("not JSON: ") + e.what());
  }
  const JsonView v(doc, file);
  v.onlyKeys({"format", "version", "osm_fnv1a64", "elements"});
  v.checkFormat(kFormat, kVersion);
  OsmSidecar out;
  out.osm_hash = v.at("osm_fnv1a64").string();
  const JsonView elements = v.at("elements");
  for (std::size_t i = 0; i < elements.size(); ++i) {
    const JsonView e = elements.at(i);
    e.onlyKeys({"element", "id", "mapfuse_id", "height", "connector_drives"});
    OsmSidecarEntry entry;
    entry.element = e.at("element").string();
    if (entry.element != "node" && entry.element != "way" && entry.element != "relation")
      e.at("element").fail("'" + entry.element + "' is not node, way or relation");
    entry.id = e.at("id").integer();
    if (auto m = e.find("mapfuse_id")) entry.mapfuse_id = m->integer();
    if (auto h = e.find("height")) entry.height = h->number(0.0, bounds::kMaxElementHeight);
    if (auto d = e.find("connector_drives"))
      entry.connector_drives = int(d->integer(0, kMaxDrives));
    out.entries.push_back(entry);
  }
  return out;
}

namespace {
/// The sidecar's map ids and heights as tags of the nodes and ways they name (io/osm_sidecar.hpp);
/// a `height` tag the file has already stays.
void applySidecar(const OsmSidecar& sidecar, Lanelet2Map& map) {
  std::unordered_map<int64_t, std::size_t> point_index;
  for (std::size_t k = 0; k < map.points.size(); ++k) point_index[map.points[k].id] = k;
  for (const auto& e : sidecar.entries) {
    std::map<std::string, std::string>* tags = nullptr;
    if (e.element == "node" && point_index.count(e.id)) tags = &map.points[point_index[e.id]].tags;
    if (e.element == "way" && map.way_index.count(e.id))
      tags = &map.linestrings[map.way_index[e.id]].tags;
    if (!tags) continue;
    if (e.mapfuse_id) (*tags)["mapfuse_id"] = std::to_string(*e.mapfuse_id);
    if (e.height) tags->emplace("height", std::to_string(*e.height));
  }
}
}  // namespace

void applyOsmSidecar(const std::filesystem::path& osm_path, const std::string& xml,
                     Lanelet2Map& map) {
  const std::filesystem::path side = osmSidecarPath(osm_path);
  if (!std::filesystem::exists(side)) return;
  const OsmSidecar sidecar = parseOsmSidecar(readBytes(side), side.string());
  if (sidecar.osm_hash != fnv1a64Hex(xml)) {
    map.sidecar = Lanelet2Map::Sidecar::kStale;
    return;
  }
  applySidecar(sidecar, map);
  map.sidecar = Lanelet2Map::Sidecar::kApplied;
}

}  // namespace mapfuse::io
