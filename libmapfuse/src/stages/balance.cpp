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
#include "mapfuse/io/tile_alignment.hpp"
#include "mapfuse/io/tiles_manifest.hpp"
#include "mapfuse/tiling/piece_links.hpp"
#include "mapfuse/tiling/placement_overview.hpp"

namespace mapfuse::stages {

namespace fs = std::filesystem;

namespace {

// One tile input: the georef piece `tile` wrote, align's output for it, its group.
struct PieceFiles {
  tiling::GroupKey group;
  std::string tile_name;
  fs::path input, aligned;
};

// The pieces of one tile, in groups, with what align did to each.
std::vector<std::pair<PieceFiles, tiling::TilePiece>> measureTile(const io::TilesManifestTile& tile,
                                                                  const fs::path& tiles_dir,
                                                                  const BalanceParams& params) {
  const io::TileAlignment t = io::readTileAlignment(tile, tiles_dir, params.aligned_subdir);
  auto links = t.kept;
  const auto agreeing =
      tiling::agreeingPieces(t.aligned, params.links.link_distance, params.links.link_min_points);
  links.insert(links.end(), agreeing.begin(), agreeing.end());
  const std::vector<int> group = tiling::registrationGroups(int(t.inputs.size()), links);
  std::vector<std::pair<PieceFiles, tiling::TilePiece>> out;
  for (std::size_t i = 0; i < t.inputs.size(); ++i) {
    const PieceFiles f{
        {{tile.ix, tile.iy}, group[i]}, tile.name, t.input_files[i], t.aligned_files[i]};
    try {
      out.emplace_back(f, tiling::measurePiece(t.inputs[i], t.aligned[i]));
    } catch (const InputError& e) {
      throw InputError(f.aligned.string() + ": " + e.what());
    }
    out.back().second.group = f.group;
  }
  return out;
}

nlohmann::json toJson(const Eigen::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}

nlohmann::json toJson(const std::vector<tiling::GroupShift>& groups) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& g : groups)
    out.push_back({{"tile", g.group.tile.name()},
                   {"group", g.group.group},
                   {"pieces", g.pieces},
                   {"shift_m", toJson(g.shift)}});
  return out;
}

nlohmann::json toJson(const std::vector<tiling::TileShift>& tiles) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& t : tiles)
    out[t.tile] = {{"groups", t.groups},
                   {"largest_group_pieces", t.largest.pieces},
                   {"largest_group_shift_m", toJson(t.largest.shift)}};
  return out;
}

}  // namespace

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
  std::vector<PieceFiles> files;
  std::vector<tiling::TilePiece> pieces;
  std::size_t total = 0;
  for (const auto& tile : manifest.tiles) total += tile.lsms.size();
  Progress progress("LSMs", 2 * total);
  for (const auto& tile : manifest.tiles)
    for (auto& [f, piece] : measureTile(tile, tiles_dir, params)) {
      files.push_back(f);
      pieces.push_back(piece);
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
  nlohmann::json summary = {{"tiles", report.tiles},
                            {"groups", report.groups},
                            {"single_piece_groups", overview.single_piece_groups},
                            {"pieces", report.pieces},
                            {"drives", report.drives},
                            {"keyframes", report.keyframes},
                            {"downweighted_pieces", report.downweighted},
                            {"rms_residual_m", report.rms_residual},
                            {"max_shift_m", report.max_shift},
                            {"largest_shifts", toJson(overview.largest_shifts)},
                            {"per_tile", toJson(overview.per_tile)},
                            {"seconds", seconds}};
  io::writeSummary(out, "balance", summary);
  outputs.commit();
  MAPFUSE_INFO("balance: " << report.pieces << " pieces of " << report.drives << " drives in "
                           << report.groups << " groups on " << report.tiles
                           << " tiles, largest shift " << report.max_shift << " m, residual rms "
                           << report.rms_residual << " m");
  return summary;
}

}  // namespace mapfuse::stages
