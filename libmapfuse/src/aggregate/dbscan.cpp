#include "mapfuse/aggregate/dbscan.hpp"

#include <deque>

namespace mapfuse::aggregate {

DbscanResult dbscan(std::size_t n, int min_pts, const NeighbourFn& neighbours) {
  constexpr int kUnvisited = -2;
  constexpr int kNoise = -1;
  DbscanResult result;
  result.labels.assign(n, kUnvisited);
  for (std::size_t i = 0; i < n; ++i) {
    if (result.labels[i] != kUnvisited) continue;
    const auto seeds = neighbours(i);
    if (int(seeds.size()) + 1 < min_pts) {
      result.labels[i] = kNoise;
      continue;
    }
    const int cluster = result.num_clusters++;
    result.labels[i] = cluster;
    std::deque<std::size_t> queue(seeds.begin(), seeds.end());
    while (!queue.empty()) {
      const std::size_t j = queue.front();
      queue.pop_front();
      if (result.labels[j] == kNoise) result.labels[j] = cluster;  // border object
      if (result.labels[j] != kUnvisited) continue;
      result.labels[j] = cluster;
      const auto nj = neighbours(j);
      if (int(nj.size()) + 1 >= min_pts)  // j is core: expand
        for (std::size_t k : nj)
          if (result.labels[k] == kUnvisited || result.labels[k] == kNoise) queue.push_back(k);
    }
  }
  for (int l : result.labels)
    if (l == kNoise) ++result.num_noise;
  return result;
}

DbscanResult dbscan(const std::vector<std::vector<std::size_t>>& neighbour_lists, int min_pts) {
  return dbscan(neighbour_lists.size(), min_pts, [&](std::size_t i) { return neighbour_lists[i]; });
}

}  // namespace mapfuse::aggregate
