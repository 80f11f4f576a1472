#include "mapfuse/stages/tile.hpp"

#include <chrono>
#include <mutex>
#include <set>

#include "mapfuse/cli/params.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/core/parallel_for.hpp"
#include "mapfuse/geo/origin.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/json_geometry.hpp"
#include "mapfuse/io/lsm_io.hpp"
#include "mapfuse/io/output_transaction.hpp"
#include "mapfuse/io/stage_report.hpp"
#include "mapfuse/tiling/split.hpp"

namespace mapfuse::stages {

namespace {
/// Tiles of an earlier tiling in `out` (their folders, with whatever later steps wrote there) and
/// tile LSMs the new tiling no longer lists: batch rules take a tile's inputs by wildcard.
void pruneStaleTiles(const std::filesystem::path& out, const nlohmann::json& manifest) {
  namespace fs = std::filesystem;
  std::set<std::string> tiles, lsms;
  for (const auto& t : manifest["tiles"]) {
    tiles.insert(t["name"].get<std::string>());
    for (const auto& f : t["lsms"]) lsms.insert(f.get<std::string>());
  }
  for (const auto& e : fs::directory_iterator(out)) {
    const std::string name = e.path().filename().string();
    if (!e.is_directory() || name.rfind("tile_", 0) != 0) continue;
    if (!tiles.count(name)) {
      fs::remove_all(e.path());
      continue;
    }
    for (const auto& f : fs::directory_iterator(e.path())) {
      const auto ext = f.path().extension();
      if (f.is_regular_file() && (ext == ".cbor" || ext == ".json") &&
          !lsms.count(name + "/" + f.path().filename().string()))
        fs::remove(f.path());
    }
  }
}
}  // namespace

nlohmann::json runTile(const std::vector<std::string>& lsm_files, const std::filesystem::path& out,
                       const TileParams& params) {
  validateParams(params);
  const auto t0 = std::chrono::steady_clock::now();
  io::OutputTransaction outputs(out);  // locked and writable before the work
  if (lsm_files.empty()) throw InputError("tile: no input LSM given");
  io::refuseSameFile(lsm_files);
  const tiling::TileGrid grid(params.tile_size, params.margin);
  // One LSM at a time per thread: read, cut, write its runs, free it. The manifest lists each
  // tile's runs in input order, as a serial run would.
  const std::size_t n = lsm_files.size();
  std::vector<std::string> drive_ids(n);
  std::vector<geo::GeoOrigin> origins(n);
  std::vector<std::map<tiling::TileKey, std::vector<std::string>>> written(n);
  std::mutex claim_mutex;
  std::set<std::string> claimed;  // drives being written: a second file of one drive writes
                                  // nothing (same tile file names), refuseSameDrive names both
  parallelFor(n, [&](std::size_t i) {
    const Lsm lsm = io::readLsm(lsm_files[i]);
    drive_ids[i] = lsm.drive_id;
    {
      const std::lock_guard<std::mutex> lock(claim_mutex);
      if (!claimed.insert(lsm.drive_id).second) return;
    }
    for (const auto& [key, runs] : tiling::splitLsm(lsm, grid, params.min_keyframes))
      for (const auto& run : runs) {
        const std::string name = key.name() + "/" + run.drive_id + "." + params.format;
        io::writeLsm(out / name, run);
        written[i][key].push_back(name);
      }
    origins[i] = *lsm.origin;  // splitLsm refuses an LSM without one
  });
  io::refuseSameDrive(lsm_files, drive_ids);
  for (std::size_t i = 1; i < n; ++i)
    if (!geo::sameOrigin(origins[i], origins[0]))
      throw InputError("LSM " + drive_ids[i] + " has another ENU origin than " + drive_ids[0]);
  std::map<tiling::TileKey, std::vector<std::string>> tiles;
  for (const auto& per_input : written)
    for (const auto& [key, names] : per_input)
      tiles[key].insert(tiles[key].end(), names.begin(), names.end());

  nlohmann::json manifest = {{"format", "mapfuse.tiles"},
                             {"version", 1},
                             {"tile_size", params.tile_size},
                             {"margin", params.margin},
                             {"origin", io::originToJson(origins[0])},
                             {"tiles", nlohmann::json::array()}};
  std::size_t files = 0;
  for (const auto& [key, names] : tiles) {
    const tiling::Rect core = grid.core(key);
    manifest["tiles"].push_back({{"name", key.name()},
                                 {"ix", key.ix},
                                 {"iy", key.iy},
                                 {"core", {core.min_x, core.min_y, core.max_x, core.max_y}},
                                 {"lsms", names}});
    files += names.size();
  }
  io::writeDocument(out / "tiles.json", manifest, 1);
  io::writeResolvedConfig(out, "tile", paramsToJson(params));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  io::writeSummary(out, "tile",
                   {{"inputs", lsm_files.size()},
                    {"tiles", tiles.size()},
                    {"tile_lsms", files},
                    {"seconds", seconds}});
  outputs.commit();
  pruneStaleTiles(out, manifest);
  MAPFUSE_INFO("tile: " << lsm_files.size() << " LSMs -> " << tiles.size() << " tiles, " << files
                        << " tile LSMs in " << out.string());
  return manifest;
}

}  // namespace mapfuse::stages
