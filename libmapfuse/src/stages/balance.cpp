#include "mapfuse/stages/balance.hpp"

#include <chrono>
#include <map>

#include "mapfuse/cli/output_guard.hpp"
#include "mapfuse/cli/params.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/core/progress.hpp"
#include "mapfuse/io/lsm_io.hpp"
#include "mapfuse/io/output_transaction.hpp"
#include "mapfuse/io/stage_report.hpp"
#include "mapfuse/io/tiles_manifest.hpp"
#include "mapfuse/tiling/placement_overview.hpp"
#include "mapfuse/tiling/tile_pieces.hpp"

namespace mapfuse::stages {

namespace fs = std::filesystem;

nlohmann::json runBalance(const fs::path& tiles_json, const fs::path& out,
                          const BalanceParams& params) {
  validateParams(params);
  const auto t0 = std::chrono::steady_clock::now();
  const io::TilesManifest manifest = io::readTilesManifest(tiles_json);
  const fs::path tiles_dir = tiles_json.parent_path();
  if (manifest.tiles.empty())
    throw InputError(tiles_json.string() + ": field 'tiles': no tiles (nothing to balance)");
  std::vector<std::string> tile_dirs{tiles_json.string()};  // what balance reads
  for (const auto& tile : manifest.tiles) tile_dirs.push_back((tiles_dir / tile.name).string());
  cli::refuseOutputOverInputs(out.string(), tile_dirs);  // exit 2 before any work
  io::OutputTransaction outputs(out);                    // locked and writable before the work

  // Pass 1, tile by tile: groups and what align did to every piece. Pass 2 reads the aligned
  // LSMs again, one at a time, so that memory holds one tile, not the whole batch.
  std::vector<tiling::MeasuredPiece> files;
  std::vector<tiling::TilePiece> pieces;
  std::size_t total = 0;
  for (const auto& tile : manifest.tiles) total += tile.lsms.size();
  Progress progress("LSMs", 2 * total);
  for (const auto& tile : manifest.tiles)
    for (auto& f : tiling::measureTilePieces(
             tile, io::readTileAlignment(tile, tiles_dir, params.aligned_subdir), params.links)) {
      pieces.push_back(std::move(f.piece));  // files keep only names and group
      files.push_back(std::move(f));
      progress.advance();
    }
  tiling::PlacementReport report;
  const auto shifts = tiling::solvePlacement(pieces, params.placement, report);

  std::map<tiling::GroupKey, int> group_size;
  for (const auto& f : files) ++group_size[f.group];
  for (const auto& f : files) {
    Lsm lsm = io::readLsm(f.aligned);
    const Eigen::Vector3d& shift = shifts.at(f.group);
    for (auto& k : lsm.keyframes) k.T_frame_body.translation() += shift;
    io::writeLsm(out / f.tile_name / f.aligned.filename(), lsm);
    progress.advance();
  }
  progress.finish();

  const auto overview = tiling::overviewOfShifts(shifts, group_size, 5);
  io::writeResolvedConfig(out, "balance", paramsToJson(params));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  nlohmann::json summary = tiling::placementSummary(report, overview);
  summary["seconds"] = seconds;
  io::writeSummary(out, "balance", summary);
  outputs.commit();
  MAPFUSE_INFO("balance: " << report.pieces << " pieces of " << report.drives << " drives in "
                           << report.groups << " groups on " << report.tiles
                           << " tiles, largest shift " << report.max_shift << " m, residual rms "
                           << report.rms_residual << " m");
  return summary;
}

}  // namespace mapfuse::stages
