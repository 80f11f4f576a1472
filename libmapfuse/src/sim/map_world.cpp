#include "mapfuse/sim/map_world.hpp"

#include <filesystem>

#include "lane_surface.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/io/lanelet2_osm.hpp"
#include "mapfuse/io/opendrive.hpp"
#include "mapfuse/io/osm_sidecar.hpp"
#include "mapfuse/sim/lanelet2_world.hpp"
#include "mapfuse/sim/opendrive_world.hpp"

namespace mapfuse::sim {

int trueMarkings(const World& world) {
  int n = 0;
  for (const auto& m : world.truth.instances) {
    const bool marking = m.cls == CrowdClass::kLaneLine || m.cls == CrowdClass::kStopLine ||
                         m.cls == CrowdClass::kCrosswalk || m.cls == CrowdClass::kGroundArrow;
    if (marking && m.note.rfind("placed by simulator", 0) != 0) ++n;
  }
  return n;
}

World loadMapWorld(const std::string& path, bool map_origin, const MapWorldSettings& settings,
                   geo::GeoOrigin* origin) {
  if (!std::filesystem::exists(path)) throw IoError(path, "map file does not exist");
  // /dev/zero, a FIFO or a folder would be read without end (2.1 GB, then out of memory).
  if (!std::filesystem::is_regular_file(path))
    throw IoError(path, "is not a regular file (a folder, device or pipe); give a map file");
  World world;
  int untyped = 0;
  if (std::filesystem::path(path).extension() == ".xodr") {
    const io::OdrMap odr = io::readOpenDrive(path);
    if (map_origin) *origin = openDriveOrigin(odr, *origin);
    world = worldFromOpenDrive(odr, *origin);
  } else {
    const io::Lanelet2Map osm = io::readLanelet2Osm(path);
    if (map_origin) {
      if (!osm.first_node) throw InputError(path + ": the map has no nodes");
      *origin = {osm.first_node->lat, osm.first_node->lon, origin->alt};
    }
    world = worldFromLanelet2(osm, *origin);
    untyped = osm.untyped_ways;
    if (osm.sidecar == io::Lanelet2Map::Sidecar::kStale)
      MAPFUSE_WARN(path << ": its sidecar " << io::osmSidecarPath(path).string()
                        << " was written for another version of this file (edited since?): "
                           "ignored, so poles have no height");
  }
  // One line per kind of repaired or dropped content (count and first example; the summary's
  // input_warnings holds the same).
  for (const auto& [kind, e] : world.warnings.entries())
    MAPFUSE_WARN(kind << ": " << e.count << "x, first: " << e.first);
  if (world.lanes.empty()) throw InputError(path + ": the map has no drivable lanes");
  world.surface_height = laneSurface(world);  // the body rolls with superelevation and banking
  const int markings = trueMarkings(world);
  world.stats["true_markings"] = markings;
  if (markings == 0) {
    const std::string why =
        path + ": the world has no true markings (lane lines, stop lines, " +
        "crosswalks or arrows in the map)" +
        (untyped > 0 ? "; " + std::to_string(untyped) + " ways have no `type` tag" : std::string());
    if (!settings.allow_no_markings)
      throw InputError(why + ". Drives would observe nothing to map; pass " +
                       "--allow-no-markings true to simulate anyway");
    MAPFUSE_WARN(why + " (allowed by allow_no_markings)");
  }
  return world;
}

}  // namespace mapfuse::sim
