#include "mapfuse/lidar/clustering.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

#include "mapfuse/core/error.hpp"
#include "mapfuse/core/union_find.hpp"

namespace mapfuse::lidar {
namespace {

uint64_t cellKey(int64_t x, int64_t y, int64_t z) {
  constexpr int64_t kBias = int64_t{1} << 20;
  constexpr uint64_t kMask = (uint64_t{1} << 21) - 1;
  return ((uint64_t(x + kBias) & kMask) << 42) | ((uint64_t(y + kBias) & kMask) << 21) |
         (uint64_t(z + kBias) & kMask);
}

}  // namespace

std::vector<int> euclideanClusters(const std::vector<Eigen::Vector3f>& points,
                                   const ClusteringSettings& s, int* num_clusters) {
  if (!(s.tolerance > 0)) throw InputError("clustering tolerance must be > 0");
  const std::size_t n = points.size();
  const float inv = static_cast<float>(1.0 / s.tolerance);
  const float tol2 = static_cast<float>(s.tolerance * s.tolerance);
  // Sort points by cell so each cell is a contiguous range.
  std::vector<std::pair<uint64_t, int>> keyed(n);
  std::vector<Eigen::Vector3i> cell(n);
  for (std::size_t i = 0; i < n; ++i) {
    cell[i] = Eigen::Vector3i(static_cast<int>(std::floor(points[i].x() * inv)),
                              static_cast<int>(std::floor(points[i].y() * inv)),
                              static_cast<int>(std::floor(points[i].z() * inv)));
    keyed[i] = {cellKey(cell[i].x(), cell[i].y(), cell[i].z()), static_cast<int>(i)};
  }
  std::sort(keyed.begin(), keyed.end());
  std::unordered_map<uint64_t, std::pair<int, int>> ranges;  // cell -> [begin, end) in keyed
  ranges.reserve(n);
  for (std::size_t b = 0; b < n;) {
    std::size_t e = b;
    while (e < n && keyed[e].first == keyed[b].first) ++e;
    ranges.emplace(keyed[b].first, std::make_pair(static_cast<int>(b), static_cast<int>(e)));
    b = e;
  }
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto unite = [&](int a, int b) {
    a = findRoot(parent, a);
    b = findRoot(parent, b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  };
  for (const auto& [key, range] : ranges) {
    const Eigen::Vector3i c = cell[keyed[range.first].second];
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const uint64_t nk = cellKey(c.x() + dx, c.y() + dy, c.z() + dz);
          if (nk < key) continue;  // each unordered cell pair once
          const auto it = ranges.find(nk);
          if (it == ranges.end()) continue;
          const bool same = nk == key;
          for (int a = range.first; a < range.second; ++a) {
            const int ia = keyed[a].second;
            for (int b = same ? a + 1 : it->second.first; b < it->second.second; ++b) {
              const int ib = keyed[b].second;
              if ((points[ia] - points[ib]).squaredNorm() <= tol2) unite(ia, ib);
            }
          }
        }
  }
  // Component sizes, then ids in order of first point.
  std::vector<int> size(n, 0);
  for (std::size_t i = 0; i < n; ++i) ++size[findRoot(parent, static_cast<int>(i))];
  std::vector<int> id_of_root(n, -2), ids(n, -1);
  int next = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const int r = findRoot(parent, static_cast<int>(i));
    if (size[r] < s.min_points) continue;
    if (id_of_root[r] == -2) id_of_root[r] = next++;
    ids[i] = id_of_root[r];
  }
  if (num_clusters) *num_clusters = next;
  return ids;
}

}  // namespace mapfuse::lidar
