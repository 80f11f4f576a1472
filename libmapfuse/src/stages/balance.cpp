#include "mapfuse/stages/balance.hpp"

#include <algorithm>
#include <chrono>
#include <map>

#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/core/params.hpp"
#include "mapfuse/core/progress.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/json_view.hpp"
#include "mapfuse/io/lsm_io.hpp"
#include "mapfuse/io/stage_report.hpp"

namespace mapfuse::stages {

namespace fs = std::filesystem;

void BalanceParams::validate() const {
  placement.validate();
  requireParam(!aligned_subdir.empty(), "BalanceParams", "aligned_subdir", aligned_subdir,
               "not empty");
}

namespace {

// One tile input: the georef piece `tile` wrote, align's output for it, its group.
struct PieceFiles {
  tiling::GroupKey group;
  std::string tile_name;
  fs::path input, aligned;
};

// Group of every input of one tile: connected components of the registrations align's pose
// graph kept (PCM-consistent, not rejected as graph outliers), read from its summary.
std::vector<PieceFiles> tilePieces(const io::JsonView& tile, const fs::path& tiles_dir,
                                   const std::string& aligned_subdir) {
  const std::string name = tile.at("name").string();
  const tiling::TileKey key{tile.at("ix").integer(), tile.at("iy").integer()};
  const fs::path align_dir = tiles_dir / name / aligned_subdir;
  const fs::path summary_path = align_dir / "align.summary.json";
  if (!fs::exists(summary_path))
    throw InputError(summary_path.string() + ": missing; run align on tile " + name +
                     " first (balance needs every tile's align output)");
  const io::Json summary_doc = io::readDocument(summary_path);
  const io::JsonView summary(summary_doc, summary_path.string());
  const io::JsonView inputs = summary.at("inputs");
  std::map<std::string, int> index_of;  // file name -> align's input index
  for (std::size_t i = 0; i < inputs.size(); ++i)
    index_of[fs::path(inputs.at(i).string()).filename().string()] = int(i);
  std::vector<std::pair<int, int>> links;
  const io::JsonView pairs = summary.at("pairs");
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const io::JsonView p = pairs.at(i);
    if (p.at("accepted").boolean() && p.at("pcm_consistent").boolean() &&
        !p.at("graph_outlier").boolean())
      links.emplace_back(int(p.at("lsm_a").integer()), int(p.at("lsm_b").integer()));
  }
  const std::vector<int> group = tiling::registrationGroups(int(inputs.size()), links);

  std::vector<PieceFiles> out;
  const io::JsonView lsms = tile.at("lsms");
  for (std::size_t i = 0; i < lsms.size(); ++i) {
    PieceFiles f;
    f.tile_name = name;
    f.input = tiles_dir / lsms.at(i).string();
    f.aligned = align_dir / f.input.filename();
    const auto it = index_of.find(f.input.filename().string());
    if (it == index_of.end() || !fs::exists(f.aligned))
      throw InputError(f.aligned.string() + ": align's output for " + f.input.string() +
                       " is missing (align tile " + name + " again)");
    f.group = {key, group[it->second]};
    out.push_back(f);
  }
  return out;
}

}  // namespace

nlohmann::json runBalance(const fs::path& tiles_json, const fs::path& out,
                          const BalanceParams& params) {
  params.validate();
  const auto t0 = std::chrono::steady_clock::now();
  const io::Json doc = io::readDocument(tiles_json);
  const io::JsonView manifest(doc, tiles_json.string());
  manifest.checkFormat("mapfuse.tiles", 1);
  const fs::path tiles_dir = tiles_json.parent_path();

  std::vector<PieceFiles> files;
  const io::JsonView tiles = manifest.at("tiles");
  for (std::size_t t = 0; t < tiles.size(); ++t) {
    auto piece_files = tilePieces(tiles.at(t), tiles_dir, params.aligned_subdir);
    files.insert(files.end(), piece_files.begin(), piece_files.end());
  }

  // Pass 1: what align did to every piece. Pass 2 reads the aligned LSMs again, one at a time,
  // so that memory holds keyframe means, not the whole batch.
  std::vector<tiling::TilePiece> pieces;
  Progress progress("LSMs", 2 * files.size());
  for (const auto& f : files) {
    try {
      pieces.push_back(tiling::measurePiece(io::readLsm(f.input), io::readLsm(f.aligned)));
    } catch (const InputError& e) {
      throw InputError(f.aligned.string() + ": " + e.what());
    }
    pieces.back().group = f.group;
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

  io::writeResolvedConfig(out, "balance", paramsToJson(params));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  nlohmann::json summary = {{"tiles", report.tiles},
                            {"groups", report.groups},
                            {"single_piece_groups", singletons},
                            {"pieces", report.pieces},
                            {"drives", report.drives},
                            {"downweighted_pieces", report.downweighted},
                            {"rms_residual_m", report.rms_residual},
                            {"max_shift_m", report.max_shift},
                            {"largest_shifts", largest},
                            {"seconds", seconds}};
  io::writeSummary(out, "balance", summary);
  MAPFUSE_INFO("balance: " << report.pieces << " pieces of " << report.drives << " drives in "
                           << report.groups << " groups on " << report.tiles
                           << " tiles, largest shift " << report.max_shift << " m, residual rms "
                           << report.rms_residual << " m");
  return summary;
}

}  // namespace mapfuse::stages
