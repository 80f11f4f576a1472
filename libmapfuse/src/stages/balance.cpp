#include "mapfuse/stages/balance.hpp"

#include <algorithm>
#include <chrono>
#include <map>

#include "mapfuse/cli/params.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/core/progress.hpp"
#include "mapfuse/io/align_registrations.hpp"
#include "mapfuse/io/lsm_io.hpp"
#include "mapfuse/io/output_transaction.hpp"
#include "mapfuse/io/stage_report.hpp"
#include "mapfuse/io/tiles_manifest.hpp"
#include "mapfuse/tiling/piece_links.hpp"

namespace mapfuse::stages {

namespace fs = std::filesystem;

namespace {

// One tile input: the georef piece `tile` wrote, align's output for it, its group.
struct PieceFiles {
  tiling::GroupKey group;
  std::string tile_name;
  fs::path input, aligned;
};

// Registrations align's pose graph kept (PCM-consistent, not rejected as graph outliers), as
// index pairs into the tile's list of inputs.
std::vector<std::pair<int, int>> keptRegistrations(const fs::path& summary_path,
                                                   const std::vector<PieceFiles>& files) {
  const io::AlignRegistrations summary = io::readAlignRegistrations(summary_path);
  std::map<std::string, int> piece_of;  // file name -> index in `files`
  for (std::size_t i = 0; i < files.size(); ++i)
    piece_of[files[i].input.filename().string()] = int(i);
  std::vector<int> piece(summary.inputs.size(), -1);  // align's input -> index in `files`
  for (std::size_t i = 0; i < summary.inputs.size(); ++i) {
    const auto it = piece_of.find(fs::path(summary.inputs[i]).filename().string());
    if (it != piece_of.end()) piece[i] = it->second;
  }
  std::vector<std::pair<int, int>> links;
  for (const auto& p : summary.pairs)
    if (p.kept && piece[p.lsm_a] >= 0 && piece[p.lsm_b] >= 0)
      links.emplace_back(piece[p.lsm_a], piece[p.lsm_b]);
  return links;
}

// The pieces of one tile, in groups, with what align did to each.
std::vector<std::pair<PieceFiles, tiling::TilePiece>> measureTile(const io::TilesManifestTile& tile,
                                                                  const fs::path& tiles_dir,
                                                                  const BalanceParams& params) {
  const std::string& name = tile.name;
  const tiling::TileKey key{tile.ix, tile.iy};
  const fs::path align_dir = tiles_dir / name / params.aligned_subdir;
  const fs::path summary_path = align_dir / "align.summary.json";
  if (!fs::exists(summary_path))
    throw InputError(summary_path.string() + ": missing; run align on tile " + name +
                     " first (balance needs every tile's align output)");
  std::vector<PieceFiles> files;
  std::vector<Lsm> inputs, aligned;
  for (const std::string& lsm : tile.lsms) {
    PieceFiles f;
    f.tile_name = name;
    f.input = tiles_dir / lsm;
    f.aligned = align_dir / f.input.filename();
    if (!fs::exists(f.aligned))
      throw InputError(f.aligned.string() + ": align's output for " + f.input.string() +
                       " is missing (align tile " + name + " again)");
    inputs.push_back(io::readLsm(f.input));
    aligned.push_back(io::readLsm(f.aligned));
    files.push_back(f);
  }
  auto links = keptRegistrations(summary_path, files);
  const auto agreeing =
      tiling::agreeingPieces(aligned, params.links.link_distance, params.links.link_min_points);
  links.insert(links.end(), agreeing.begin(), agreeing.end());
  const std::vector<int> group = tiling::registrationGroups(int(files.size()), links);

  std::vector<std::pair<PieceFiles, tiling::TilePiece>> out;
  for (std::size_t i = 0; i < files.size(); ++i) {
    files[i].group = {key, group[i]};
    try {
      out.emplace_back(files[i], tiling::measurePiece(inputs[i], aligned[i]));
    } catch (const InputError& e) {
      throw InputError(files[i].aligned.string() + ": " + e.what());
    }
    out.back().second.group = files[i].group;
  }
  return out;
}

}  // namespace

nlohmann::json runBalance(const fs::path& tiles_json, const fs::path& out,
                          const BalanceParams& params) {
  validateParams(params);
  const auto t0 = std::chrono::steady_clock::now();
  io::OutputTransaction outputs(out);  // locked and writable before the work
  const io::TilesManifest manifest = io::readTilesManifest(tiles_json);
  const fs::path tiles_dir = tiles_json.parent_path();

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

  // The largest moves, for a look at where tiles disagreed most.
  std::vector<std::pair<double, tiling::GroupKey>> moved;
  for (const auto& [key, s] : shifts) moved.emplace_back(s.head<2>().norm(), key);
  std::sort(moved.rbegin(), moved.rend());
  nlohmann::json largest = nlohmann::json::array();
  for (std::size_t i = 0; i < std::min<std::size_t>(5, moved.size()); ++i) {
    const auto& key = moved[i].second;
    const Eigen::Vector3d& s = shifts.at(key);
    largest.push_back({{"tile", key.tile.name()},
                       {"group", key.group},
                       {"pieces", group_size[key]},
                       {"shift_m", {s.x(), s.y(), s.z()}}});
  }
  int singletons = 0;
  for (const auto& [key, n] : group_size) singletons += n == 1;
  // Per tile: its groups and the move of its largest one (most of the tile's map).
  std::map<std::string, std::pair<int, tiling::GroupKey>> main_group;  // pieces, group
  std::map<std::string, int> groups_in;
  for (const auto& [key, n] : group_size) {
    ++groups_in[key.tile.name()];
    auto& m = main_group[key.tile.name()];
    if (n > m.first) m = {n, key};
  }
  nlohmann::json per_tile = nlohmann::json::object();
  for (const auto& [name, m] : main_group) {
    const Eigen::Vector3d& s = shifts.at(m.second);
    per_tile[name] = {{"groups", groups_in[name]},
                      {"largest_group_pieces", m.first},
                      {"largest_group_shift_m", {s.x(), s.y(), s.z()}}};
  }

  io::writeResolvedConfig(out, "balance", paramsToJson(params));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  nlohmann::json summary = {{"tiles", report.tiles},
                            {"groups", report.groups},
                            {"single_piece_groups", singletons},
                            {"pieces", report.pieces},
                            {"drives", report.drives},
                            {"keyframes", report.keyframes},
                            {"downweighted_pieces", report.downweighted},
                            {"rms_residual_m", report.rms_residual},
                            {"max_shift_m", report.max_shift},
                            {"largest_shifts", largest},
                            {"per_tile", per_tile},
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
