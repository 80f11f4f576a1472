#include "mapfuse/stages/info.hpp"

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/json_geometry.hpp"
#include "mapfuse/io/lsm_io.hpp"
#include "mapfuse/io/vector_map_io.hpp"

namespace mapfuse::stages {
namespace {

nlohmann::json describeLsm(const Lsm& lsm) {
  double length = 0.0;
  for (std::size_t i = 1; i < lsm.keyframes.size(); ++i)
    length += (lsm.keyframes[i].T_frame_body.translation() -
               lsm.keyframes[i - 1].T_frame_body.translation())
                  .norm();
  nlohmann::json per_class = nlohmann::json::object();
  for (const auto& e : lsm.elements)
    per_class[crowdClassName(e.cls)] = per_class.value(crowdClassName(e.cls), 0) + 1;
  nlohmann::json j = {{"drive_id", lsm.drive_id},
                      {"vehicle_id", lsm.vehicle_id},
                      {"frame", lsm.frame == LsmFrame::kEnu ? "enu" : "odom"},
                      {"keyframes", lsm.keyframes.size()},
                      {"gps_fixes", lsm.gps.size()},
                      {"elements", lsm.elements.size()},
                      {"elements_per_class", per_class},
                      {"trajectory_length_m", length}};
  if (!lsm.keyframes.empty())
    j["duration_s"] = lsm.keyframes.back().stamp - lsm.keyframes.front().stamp;
  if (lsm.origin) j["origin"] = io::originToJson(*lsm.origin);
  return j;
}

nlohmann::json describeMap(const VectorMap& map) {
  nlohmann::json per_class = nlohmann::json::object();
  for (const auto& i : map.instances)
    per_class[crowdClassName(i.cls)] = per_class.value(crowdClassName(i.cls), 0) + 1;
  return {{"source", map.source},
          {"origin", io::originToJson(map.origin)},
          {"instances", map.instances.size()},
          {"instances_per_class", per_class},
          {"lane_line_length_m", totalLineLength(map, CrowdClass::kLaneLine)}};
}

}  // namespace

nlohmann::json describeFile(const std::filesystem::path& path) {
  const nlohmann::json doc = io::readDocument(path);
  const std::string file = path.string();
  if (!doc.is_object() || !doc.contains("format") || !doc["format"].is_string())
    throw ParseError(file, "format", "not a mapfuse document (no \"format\" string)");
  const std::string format = doc["format"];
  nlohmann::json j;
  if (format == io::kLsmFormat)
    j = describeLsm(io::lsmFromJson(doc, file));
  else if (format == io::kVectorMapFormat)
    j = describeMap(io::vectorMapFromJson(doc, file));
  else if (format == "mapfuse.tiles")
    j = {{"tiles", doc.value("tiles", nlohmann::json::array()).size()}};
  else if (format == "mapfuse.summary")
    j = {{"stage", doc.value("stage", "")}};
  else
    throw ParseError(file, "format", "unknown format \"" + format + "\"");
  j["file"] = file;
  j["format"] = format;
  j["bytes"] = std::filesystem::file_size(path);
  return j;
}

geo::GeoOrigin originOfLsm(const std::filesystem::path& path) {
  const Lsm lsm = io::readLsm(path);
  if (lsm.origin) return *lsm.origin;
  if (lsm.gps.empty())
    throw InputError(path.string() + ": no origin and no GPS fix to derive one from");
  return lsm.gps.front().position;
}

}  // namespace mapfuse::stages
