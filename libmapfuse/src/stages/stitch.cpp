#include "mapfuse/stages/stitch.hpp"

#include <chrono>
#include <regex>

#include "mapfuse/cli/params.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/geojson.hpp"
#include "mapfuse/io/json_view.hpp"
#include "mapfuse/io/output_transaction.hpp"
#include "mapfuse/io/stage_report.hpp"
#include "mapfuse/io/tiles_manifest.hpp"
#include "mapfuse/io/vector_map_io.hpp"

namespace mapfuse::stages {

tiling::TileKey tileOfPath(const std::filesystem::path& path) {
  static const std::regex kTile("tile_(m?)([0-9]+)_(m?)([0-9]+)");
  std::optional<tiling::TileKey> key;
  for (const auto& part : path) {
    std::smatch m;
    const std::string s = part.string();
    if (std::regex_match(s, m, kTile))
      if (m[2].length() <= 15 && m[4].length() <= 15)  // std::stoll cannot overflow
        key = tiling::TileKey{(m[1] == "m" ? -1 : 1) * std::stoll(m[2]),
                              (m[3] == "m" ? -1 : 1) * std::stoll(m[4])};
  }
  if (!key) throw ParseError(path.string(), "", "no tile_<ix>_<iy> folder in the path");
  return *key;
}

VectorMap runStitch(const std::filesystem::path& tiles_json, const std::vector<std::string>& maps,
                    const std::filesystem::path& out_map, const tiling::StitchParams& params) {
  validateParams(params);
  const auto t0 = std::chrono::steady_clock::now();
  const auto dir = out_map.has_parent_path() ? out_map.parent_path() : std::filesystem::path(".");
  const io::TilesManifest manifest = io::readTilesManifest(tiles_json);
  const auto tile_of = io::tileOfEachMap(manifest, tiles_json.string(), maps);  // each tile once
  io::OutputTransaction outputs(dir);  // locked and writable before the work
  const tiling::TileGrid grid(manifest.tile_size, manifest.margin);

  std::vector<std::pair<tiling::TileKey, VectorMap>> tiles;
  for (std::size_t i = 0; i < maps.size(); ++i) {
    const auto& t = manifest.tiles[tile_of[i]];
    tiles.emplace_back(tiling::TileKey{t.ix, t.iy}, io::readVectorMap(maps[i]));
  }
  tiling::StitchReport report;
  const VectorMap stitched = tiling::stitchTiles(tiles, grid, params, report);

  io::writeVectorMap(out_map, stitched);
  auto geojson = out_map;
  io::writeGeoJson(geojson.replace_extension(".geojson"), stitched);
  io::writeResolvedConfig(dir, "stitch", paramsToJson(params));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  io::writeSummary(dir, "stitch",
                   {{"tiles", report.tiles},
                    {"instances_in", report.instances_in},
                    {"instances_out", report.instances_out},
                    {"dropped_outside_core", report.dropped_outside_core},
                    {"line_pieces", report.line_pieces},
                    {"joins", report.joins},
                    {"seconds", seconds}});
  outputs.commit();
  MAPFUSE_INFO("stitch: " << report.tiles << " tiles, " << report.instances_in << " -> "
                          << report.instances_out << " instances, " << report.joins << " joins");
  return stitched;
}

}  // namespace mapfuse::stages
