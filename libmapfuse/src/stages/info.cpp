#include "mapfuse/stages/info.hpp"

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/json_geometry.hpp"
#include "mapfuse/io/lsm_io.hpp"
#include "mapfuse/io/vector_map_io.hpp"

namespace mapfuse::stages {
namespace {

LsmInfo describeLsm(const Lsm& lsm) {
  LsmInfo info;
  info.drive_id = lsm.drive_id;
  info.vehicle_id = lsm.vehicle_id;
  info.frame = lsm.frame == LsmFrame::kEnu ? "enu" : "odom";
  info.keyframes = lsm.keyframes.size();
  info.gps_fixes = lsm.gps.size();
  info.elements = lsm.elements.size();
  for (const auto& e : lsm.elements) ++info.elements_per_class[crowdClassName(e.cls)];
  for (std::size_t i = 1; i < lsm.keyframes.size(); ++i)
    info.trajectory_length_m += (lsm.keyframes[i].T_frame_body.translation() -
                                 lsm.keyframes[i - 1].T_frame_body.translation())
                                    .norm();
  if (!lsm.keyframes.empty())
    info.duration_s = lsm.keyframes.back().stamp - lsm.keyframes.front().stamp;
  info.origin = lsm.origin;
  return info;
}

MapInfo describeMap(const VectorMap& map) {
  MapInfo info;
  info.source = map.source;
  info.origin = map.origin;
  info.instances = map.instances.size();
  for (const auto& i : map.instances) ++info.instances_per_class[crowdClassName(i.cls)];
  info.lane_line_length_m = totalLineLength(map, CrowdClass::kLaneLine);
  return info;
}

}  // namespace

nlohmann::json toJson(const FileInfo& info) {
  nlohmann::json j;
  if (const auto& l = info.lsm) {
    j = {{"drive_id", l->drive_id},
         {"vehicle_id", l->vehicle_id},
         {"frame", l->frame},
         {"keyframes", l->keyframes},
         {"gps_fixes", l->gps_fixes},
         {"elements", l->elements},
         {"elements_per_class", l->elements_per_class},
         {"trajectory_length_m", l->trajectory_length_m}};
    if (l->duration_s) j["duration_s"] = *l->duration_s;
    if (l->origin) j["origin"] = io::originToJson(*l->origin);
  } else if (const auto& m = info.map) {
    j = {{"source", m->source},
         {"origin", io::originToJson(m->origin)},
         {"instances", m->instances},
         {"instances_per_class", m->instances_per_class},
         {"lane_line_length_m", m->lane_line_length_m}};
  } else if (info.format == "mapfuse.tiles") {
    j = {{"tiles", info.tiles}};
  } else {
    j = {{"stage", info.stage}};
  }
  j["file"] = info.file;
  j["format"] = info.format;
  j["bytes"] = info.bytes;
  return j;
}

FileInfo describeFile(const std::filesystem::path& path) {
  const nlohmann::json doc = io::readDocument(path);
  FileInfo info;
  info.file = path.string();
  if (!doc.is_object() || !doc.contains("format") || !doc["format"].is_string())
    throw ParseError(info.file, "format", "not a mapfuse document (no \"format\" string)");
  info.format = doc["format"];
  if (info.format == io::kLsmFormat)
    info.lsm = describeLsm(io::lsmFromJson(doc, info.file));
  else if (info.format == io::kVectorMapFormat)
    info.map = describeMap(io::vectorMapFromJson(doc, info.file));
  else if (info.format == "mapfuse.tiles")
    info.tiles = doc.value("tiles", nlohmann::json::array()).size();
  else if (info.format == "mapfuse.summary")
    info.stage = doc.value("stage", "");
  else
    throw ParseError(info.file, "format", "unknown format \"" + info.format + "\"");
  info.bytes = std::filesystem::file_size(path);
  return info;
}

geo::GeoOrigin originOf(const std::filesystem::path& path) {
  const nlohmann::json doc = io::readDocument(path);
  if (doc.is_object() && doc.value("format", "") == io::kVectorMapFormat)
    return io::vectorMapFromJson(doc, path.string()).origin;  // a map update's batch
  const Lsm lsm = io::lsmFromJson(doc, path.string());
  if (lsm.origin) return *lsm.origin;
  if (lsm.gps.empty())
    throw InputError(path.string() + ": no origin and no GPS fix to derive one from");
  return lsm.gps.front().position;
}

}  // namespace mapfuse::stages
