#include "mapfuse/tiling/split.hpp"

#include <cmath>
#include <unordered_set>

#include "mapfuse/core/error.hpp"

namespace mapfuse::tiling {
namespace {

// Copies keyframes [first, last] of `src` with their elements and GPS fixes.
Lsm extractRun(const Lsm& src, std::size_t first, std::size_t last, double gps_slack) {
  Lsm run;
  run.drive_id = src.drive_id;
  run.vehicle_id = src.vehicle_id;
  run.frame = src.frame;
  run.origin = src.origin;
  run.keyframes.assign(src.keyframes.begin() + first, src.keyframes.begin() + last + 1);
  std::unordered_set<int64_t> ids;
  for (const auto& k : run.keyframes) ids.insert(k.id);
  for (const auto& e : src.elements)
    if (ids.count(e.anchor)) run.elements.push_back(e);
  const double t0 = run.keyframes.front().stamp - gps_slack;
  const double t1 = run.keyframes.back().stamp + gps_slack;
  for (const auto& g : src.gps)
    if (g.stamp >= t0 && g.stamp <= t1) run.gps.push_back(g);
  return run;
}

}  // namespace

std::map<TileKey, std::vector<Lsm>> splitLsm(const Lsm& lsm, const TileGrid& grid,
                                             int min_keyframes, double gps_slack) {
  if (lsm.frame != LsmFrame::kEnu || !lsm.origin)
    throw InputError("LSM " + lsm.drive_id + " is not georeferenced (frame must be enu)");
  // Every tile whose margin rectangle a keyframe falls in.
  std::map<TileKey, std::vector<bool>> inside;
  const std::size_t n = lsm.keyframes.size();
  for (std::size_t i = 0; i < n; ++i) {
    const auto& t = lsm.keyframes[i].T_frame_body.translation();
    for (const TileKey& k : grid.tilesTouching(t.x(), t.y())) {
      auto& flags = inside[k];
      flags.resize(n, false);
      flags[i] = true;
    }
  }
  std::map<TileKey, std::vector<Lsm>> tiles;
  for (const auto& [key, flags] : inside) {
    std::vector<Lsm> runs;
    for (std::size_t i = 0; i < n;) {
      if (!flags[i]) {
        ++i;
        continue;
      }
      std::size_t j = i;
      while (j + 1 < n && flags[j + 1]) ++j;
      if (int(j - i + 1) >= min_keyframes) runs.push_back(extractRun(lsm, i, j, gps_slack));
      i = j + 1;
    }
    if (runs.size() > 1)
      for (std::size_t r = 0; r < runs.size(); ++r)
        runs[r].drive_id = lsm.drive_id + ".run" + std::to_string(r);
    if (!runs.empty()) tiles[key] = std::move(runs);
  }
  return tiles;
}

}  // namespace mapfuse::tiling
