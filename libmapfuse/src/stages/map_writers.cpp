#include "map_writers.hpp"

#include "mapfuse/io/geojson.hpp"
#include "mapfuse/lanelet/regulatory.hpp"

namespace mapfuse::stages {

std::vector<std::function<void()>> vectorMapWriters(const std::filesystem::path& out_dir,
                                                    const VectorMap& map,
                                                    const std::vector<Lsm>& drives,
                                                    const lanelet::LaneletSettings& lanelet,
                                                    const io::VectorMapWriteOptions& cbor,
                                                    io::Lanelet2ExportStats* osm_stats) {
  return {[&, out_dir, osm_stats] {  // the slowest first
            io::writeOsm(out_dir / "map.osm", map,
                         lanelet::planExport(map, lanelet::drivePaths(drives), lanelet), osm_stats);
          },
          [&, out_dir, cbor] { io::writeVectorMap(out_dir / "map.cbor", map, cbor); },
          [&, out_dir] { io::writeVectorMap(out_dir / "map.json", map); },
          [&, out_dir] { io::writeGeoJson(out_dir / "map.geojson", map); }};
}

}  // namespace mapfuse::stages
