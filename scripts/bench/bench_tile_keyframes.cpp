// Where a tiled run puts each tile, against the simulator's truth and the untiled run: per tile,
// the mean error (estimate - truth) of the keyframes its core holds, for the untiled align, the
// tile's own align and balance's output; over the tiles, the keyframe-weighted RMS of those
// horizontal means (docs/scaling.md "Why balance"). Also how far the pieces of one tile sit from
// each other after the tile's own align: RMS over pieces of (piece mean error - mean over the
// tile's pieces), which says whether a tile is one rigid block.
//
//   bench_tile_keyframes --sim SIM --tiled WORK --untiled WORK   -> one JSON line on stdout
#include <CLI/CLI.hpp>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>

#include "mapfuse/cli/app.hpp"
#include "mapfuse/eval/trajectory_metrics.hpp"
#include "mapfuse/geo/origin.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/lsm_io.hpp"
#include "mapfuse/tiling/placement.hpp"
#include "mapfuse/tiling/tile_grid.hpp"

using namespace mapfuse;
namespace fs = std::filesystem;

namespace {

// True keyframe positions of one drive in the batch's ENU, by stamp.
struct Truth {
  eval::TrueTrajectory trajectory;
  std::vector<const eval::TruePose*> sorted;
};

std::map<int64_t, Eigen::Vector3d> positions(const Lsm& lsm) {
  std::map<int64_t, Eigen::Vector3d> out;
  for (const auto& k : lsm.keyframes) out[k.id] = k.T_frame_body.translation();
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"per-tile keyframe placement of a tiled run vs truth and the untiled run"};
  std::string sim, tiled, untiled;
  app.add_option("--sim", sim, "simulate output folder (truth/ inside)")->required();
  app.add_option("--tiled", tiled, "crowd.mk work folder of the tiled run")->required();
  app.add_option("--untiled", untiled, "crowd.mk work folder of the untiled run")->required();
  return cli::run(app, argc, argv, [&] {
    const io::Json manifest = io::readDocument(fs::path(tiled) / "tiles" / "tiles.json");
    std::map<std::string, Truth> truth;
    std::map<std::string, std::map<int64_t, Eigen::Vector3d>> untiled_kf;
    for (const auto& e : fs::directory_iterator(fs::path(untiled) / "align"))
      if (e.path().extension() == ".cbor" || e.path().extension() == ".json")
        if (e.path().filename().string().find(".summary.") == std::string::npos &&
            e.path().filename().string().find(".config.") == std::string::npos) {
          const Lsm lsm = io::readLsm(e.path());
          untiled_kf[lsm.drive_id] = positions(lsm);
        }
    // Sums over tiles of keyframes * |mean error|^2, per variant, and of the differences.
    double n = 0, sq_untiled = 0, sq_tiled = 0, sq_balanced = 0, sq_t_u = 0, sq_b_u = 0;
    double sq_spread = 0;
    int spread_pieces = 0;
    for (const auto& tile : manifest["tiles"]) {
      const std::string name = tile["name"];
      const tiling::Rect core{tile["core"][0], tile["core"][1], tile["core"][2], tile["core"][3]};
      Eigen::Vector3d e_u = Eigen::Vector3d::Zero(), e_t = e_u, e_b = e_u;
      int k = 0;
      std::vector<Eigen::Vector3d> piece_means;  // own align - truth, over a piece's keyframes
      for (const auto& rel : tile["lsms"]) {
        const fs::path file = fs::path(rel.get<std::string>()).filename();
        const Lsm aligned = io::readLsm(fs::path(tiled) / "tiles" / name / "align" / file);
        const auto balanced = positions(io::readLsm(fs::path(tiled) / "balance" / name / file));
        const std::string drive = tiling::driveOfPiece(aligned.drive_id);
        auto& t = truth[drive];
        if (t.sorted.empty()) {
          t.trajectory =
              eval::readTrueTrajectory(fs::path(sim) / "truth" / (drive + ".trajectory.json"));
          t.sorted = eval::sortedByStamp(t.trajectory);
        }
        const geo::EnuConverter from(t.trajectory.origin), to(*aligned.origin);
        const auto& u = untiled_kf.at(drive);
        Eigen::Vector3d piece_sum = Eigen::Vector3d::Zero();
        int piece_k = 0;
        for (const auto& kf : aligned.keyframes) {
          const Eigen::Vector3d p = kf.T_frame_body.translation();
          const auto pose = eval::truePoseAt(t.sorted, kf.stamp);
          if (!pose) continue;
          const Eigen::Vector3d truth_enu = to.toEnu(from.toWgs84(pose->translation()));
          piece_sum += p - truth_enu;
          ++piece_k;
          if (!core.ownsPoint(p.x(), p.y())) continue;
          e_t += p - truth_enu;
          e_u += u.at(kf.id) - truth_enu;
          e_b += balanced.at(kf.id) - truth_enu;
          ++k;
        }
        if (piece_k > 0) piece_means.push_back(piece_sum / piece_k);
      }
      if (!piece_means.empty()) {
        Eigen::Vector3d mean = Eigen::Vector3d::Zero();
        for (const auto& m : piece_means) mean += m / double(piece_means.size());
        for (const auto& m : piece_means) sq_spread += (m - mean).head<2>().squaredNorm();
        spread_pieces += int(piece_means.size());
      }
      if (k == 0) continue;
      e_u /= k, e_t /= k, e_b /= k;
      n += k;
      sq_untiled += k * e_u.head<2>().squaredNorm();
      sq_tiled += k * e_t.head<2>().squaredNorm();
      sq_balanced += k * e_b.head<2>().squaredNorm();
      sq_t_u += k * (e_t - e_u).head<2>().squaredNorm();
      sq_b_u += k * (e_b - e_u).head<2>().squaredNorm();
    }
    if (n == 0) throw InputError("no tile holds a keyframe in its core");
    std::cout << nlohmann::json{{"keyframes", n},
                                {"untiled_m", std::sqrt(sq_untiled / n)},
                                {"tiled_m", std::sqrt(sq_tiled / n)},
                                {"balanced_m", std::sqrt(sq_balanced / n)},
                                {"tiled_minus_untiled_m", std::sqrt(sq_t_u / n)},
                                {"balanced_minus_untiled_m", std::sqrt(sq_b_u / n)},
                                {"piece_spread_in_tile_m", std::sqrt(sq_spread / spread_pieces)}}
                     .dump()
              << '\n';
  });
}
