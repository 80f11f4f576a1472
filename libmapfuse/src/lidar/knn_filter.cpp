// K-nearest-voxel mean-distance filter (Jeong et al. 2018, §2.2) over the voxel keys sorted in
// (x, y, z) order: the voxels are visited in that order, and for the first shell (the 26 cells
// around a voxel, where nearly every voxel of a surface is decided) each of the 9 neighbouring
// (x, y) columns is a contiguous run found by a cursor that only moves forward. The few voxels
// left open after the first shell (edges, isolated voxels) continue shell by shell with searches
// started from their own position. The verdict is the one of the cube-shell search over the hash
// index that this replaces: same distances, same stopping rule.
#include <algorithm>
#include <cmath>
#include <string>

#include "mapfuse/core/error.hpp"
#include "mapfuse/lidar/refinement.hpp"
#include "sorted_voxel_keys.hpp"

namespace mapfuse::lidar {
namespace {

/// K smallest values seen so far (ascending), K <= 32.
struct SmallestK {
  explicit SmallestK(int k) : k(k) {}
  void push(double v) {
    if (n == k && v >= d[n - 1]) return;
    int i = n < k ? n++ : n - 1;
    while (i > 0 && d[i - 1] > v) {
      d[i] = d[i - 1];
      --i;
    }
    d[i] = v;
  }
  int k, n = 0;
  double d[32];
};

enum class Verdict { kOpen, kKeep, kDrop };

class KnnSearch {
 public:
  KnnSearch(const detail::SortedVoxelKeys& s, double vs, const KnnFilterSettings& settings)
      : s_(s),
        k_(s.keys()),
        n_(s.size()),
        vs_(vs),
        K_(settings.k),
        delta_(settings.max_mean_distance),
        max_shell_(static_cast<int>(std::ceil(K_ * delta_ / vs)) + 1) {
    const int r = std::min(max_shell_, 32);
    dist_.resize(3 * r * r + 1);
    for (std::size_t d2 = 0; d2 < dist_.size(); ++d2) dist_[d2] = vs_ * std::sqrt(double(d2));
  }

  /// Verdict for the voxel at sorted position p; `cursors` (9, one per column around it, row
  /// major in (dx, dy)) are search hints that must only be used for ascending p.
  bool keep(std::size_t p, std::size_t* cursors) const {
    const uint64_t key = k_[p];
    const int64_t x = s_.x(key), y = s_.y(key), z = s_.z(key);
    SmallestK best(K_);
    for (int dx = -1, c = 0; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy, ++c)
        cursors[c] = visitColumn(cursors[c], x, y, z, dx, dy, -1, 1, best);
    Verdict v = decide(best, 1);
    for (int r = 2; r <= max_shell_ && v == Verdict::kOpen; ++r) {
      visitShell(p, x, y, z, r, best);
      v = decide(best, r);
    }
    return v == Verdict::kKeep;
  }

 private:
  double distance(int d2) const {
    return d2 < static_cast<int>(dist_.size()) ? dist_[d2] : vs_ * std::sqrt(double(d2));
  }

  /// Pushes the distances to the voxels of column (x + dx, y + dy) with z in [z + dz0, z + dz1],
  /// except the voxel (x, y, z) itself. Searches from `pos`; returns the lower bound of the
  /// column's first cell (or `pos` when the column is outside the map's box).
  std::size_t visitColumn(std::size_t pos, int64_t x, int64_t y, int64_t z, int dx, int dy, int dz0,
                          int dz1, SmallestK& best) const {
    const int64_t cx = x + dx, cy = y + dy;
    if (cx < 0 || cx >= s_.nx() || cy < 0 || cy >= s_.ny()) return pos;
    const int64_t z0 = std::max<int64_t>(z + dz0, 0), z1 = std::min<int64_t>(z + dz1, s_.nz() - 1);
    if (z0 > z1) return pos;
    const uint64_t hi = s_.key(cx, cy, z1);
    pos = detail::lowerBoundFrom(k_, n_, pos, s_.key(cx, cy, z0));
    for (std::size_t j = pos; j < n_ && k_[j] <= hi; ++j) {
      const int dz = static_cast<int>(s_.z(k_[j]) - z);
      if (dx != 0 || dy != 0 || dz != 0) best.push(distance(dx * dx + dy * dy + dz * dz));
    }
    return pos;
  }

  /// Visits the cells at Chebyshev distance exactly r (r >= 2) from the voxel at sorted
  /// position p, in ascending key order.
  void visitShell(std::size_t p, int64_t x, int64_t y, int64_t z, int r, SmallestK& best) const {
    std::size_t pos = p;
    for (int dx = -r; dx <= r; ++dx)
      for (int dy = -r; dy <= r; ++dy) {
        if (std::abs(dx) == r || std::abs(dy) == r) {
          pos = visitColumn(pos, x, y, z, dx, dy, -r, r, best);
        } else {
          pos = visitColumn(pos, x, y, z, dx, dy, -r, -r, best);
          pos = visitColumn(pos, x, y, z, dx, dy, r, r, best);
        }
      }
  }

  /// The stopping rule once every voxel within Chebyshev distance r is in `best`.
  Verdict decide(const SmallestK& best, int r) const {
    // Unvisited voxels are at least (r + 1) voxels away.
    const double beyond = (r + 1) * vs_;
    double lower = 0;
    for (int j = 0; j < K_; ++j) lower += j < best.n ? std::min(best.d[j], beyond) : beyond;
    lower /= K_;
    if (lower > delta_) return Verdict::kDrop;
    if (best.n == K_ && best.d[K_ - 1] <= beyond) {
      double mean = 0;
      for (int j = 0; j < K_; ++j) mean += best.d[j];
      return mean / K_ <= delta_ ? Verdict::kKeep : Verdict::kDrop;
    }
    return Verdict::kOpen;
  }

  const detail::SortedVoxelKeys& s_;
  const uint64_t* k_;
  std::size_t n_;
  double vs_;
  int K_;
  double delta_;
  int max_shell_;
  std::vector<double> dist_;  ///< dist_[d2] = vs * sqrt(d2)
};

}  // namespace

std::vector<uint8_t> knnMeanDistanceFilter(const SemanticVoxelMap& map, const KnnFilterSettings& s,
                                           int num_threads) {
  if (s.k < 1 || s.k > 32)
    throw InputError("KnnFilterSettings::k = " + std::to_string(s.k) + ": must be in 1..32");
  if (!(s.max_mean_distance > 0))
    throw InputError("KnnFilterSettings::max_mean_distance = " +
                     std::to_string(s.max_mean_distance) + ": must be > 0");
  std::vector<uint8_t> keep(map.size(), 0);
  const detail::SortedVoxelKeys sorted(map);
  const KnnSearch search(sorted, map.voxelSize(), s);
  // Chunks of the sorted order, each swept with its own cursors.
  constexpr std::size_t kChunk = std::size_t{1} << 14;
  const std::size_t n = sorted.size();
  const long long chunks = static_cast<long long>((n + kChunk - 1) / kChunk);
#pragma omp parallel for schedule(dynamic, 1) num_threads(std::max(1, num_threads))
  for (long long c = 0; c < chunks; ++c) {
    const std::size_t begin = static_cast<std::size_t>(c) * kChunk;
    const std::size_t end = std::min(n, begin + kChunk);
    std::size_t cursors[9];
    std::fill(cursors, cursors + 9, begin);
    for (std::size_t p = begin; p < end; ++p)
      keep[sorted.voxelIndex(p)] = search.keep(p, cursors) ? 1 : 0;
  }
  return keep;
}

}  // namespace mapfuse::lidar
