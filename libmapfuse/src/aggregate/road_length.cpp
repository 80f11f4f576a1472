#include "mapfuse/aggregate/road_length.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <unordered_set>

#include "mapfuse/core/voxel_grid.hpp"
#include "mapfuse/io/bounds.hpp"

namespace mapfuse::aggregate {

double coveredRoadKm(const std::vector<Lsm>& lsms, const RoadLengthSettings& settings) {
  const double tolerance = settings.tolerance;
  using voxel_grid::cellKey2d;
  auto key = [&](const Eigen::Vector3d& p) { return cellKey2d(p.x(), p.y(), tolerance); };
  std::unordered_multimap<int64_t, Eigen::Vector3d> accepted;
  // Cells of tolerance / 1.5 holding an accepted sample: any two points in one such cell lie
  // within 0.943 tolerance, so a sample whose cell is taken is known without a search (the
  // answer the search would give; with many drives on a road nearly every sample's is).
  const double fine = tolerance / 1.5;
  auto fineKey = [&](const Eigen::Vector3d& p) { return cellKey2d(p.x(), p.y(), fine); };
  std::unordered_set<int64_t> taken;
  double metres = 0.0;
  for (const Lsm& lsm : lsms) {
    std::vector<Eigen::Vector3d> samples;
    for (std::size_t i = 1; i < lsm.keyframes.size(); ++i) {
      const Eigen::Vector3d a = lsm.keyframes[i - 1].T_frame_body.translation();
      const Eigen::Vector3d b = lsm.keyframes[i].T_frame_body.translation();
      // A step longer than the readers' keyframe gap (io/bounds.hpp) is not road the drive saw;
      // the readers refuse such steps, this keeps the 1 m sampling bounded regardless.
      if ((b - a).norm() > io::bounds::kMaxKeyframeGap) continue;
      const int n = std::max(1, int(std::ceil((b - a).norm())));
      for (int k = 0; k < n; ++k) samples.push_back(a + (b - a) * (double(k) + 0.5) / n);
      const double step = (b - a).norm() / n;
      for (int k = 0; k < n; ++k) {
        const Eigen::Vector3d& s = samples[samples.size() - n + k];
        bool known = taken.count(fineKey(s)) > 0;
        const int64_t ix = int64_t(std::floor(s.x() / tolerance));
        const int64_t iy = int64_t(std::floor(s.y() / tolerance));
        // The sample's own cell first: with many drives on a road its first sample there already
        // answers (the other cells may hold hundreds of samples farther than the tolerance).
        // c = 1..9 are the 3 x 3 block, the own cell (c = 5) skipped (until 2026-11-25 c stopped
        // at 8: the (+1, +1) cell was never searched and its road counted twice).
        for (int c = 0; c < 10 && !known; ++c) {
          const int64_t dx = c == 0 ? 0 : (c - 1) % 3 - 1, dy = c == 0 ? 0 : (c - 1) / 3 - 1;
          if (c > 0 && dx == 0 && dy == 0) continue;
          auto range = accepted.equal_range(cellKey2d(ix + dx, iy + dy));
          for (auto it = range.first; it != range.second && !known; ++it)
            known = (it->second - s).head<2>().norm() <= tolerance;
        }
        if (!known) metres += step;
      }
    }
    for (const auto& s : samples) {
      accepted.emplace(key(s), s);
      taken.insert(fineKey(s));
    }
  }
  return metres / 1000.0;
}

}  // namespace mapfuse::aggregate
