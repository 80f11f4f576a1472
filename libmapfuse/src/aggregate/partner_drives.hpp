#pragma once
/// @file Bounded comparisons between the observations of many drives (private to
/// libmapfuse/src/aggregate). With n drives on a road, comparing every observation with every
/// other one costs O(n^2) per place; DBSCAN needs only enough neighbours per observation to find
/// the core ones and to connect a cluster. Each observation is therefore compared with those of
/// at most k other drives present there: all of them when there are no more than k, otherwise k
/// evenly spread over the sorted list with a rotating start, so that different drives and
/// different places pick different partners and a cluster's comparison graph stays connected
/// (a circulant graph over the drives). O(k) comparisons per observation.
#include <algorithm>
#include <cstdint>
#include <vector>

namespace mapfuse::aggregate::detail {

/// @brief The drives of `present` (sorted, unique) to compare an observation of drive `own` with,
/// sorted: its own and every other one when `k` <= 0 or there are at most k others, else its own
/// and k others evenly spread, starting at `offset` (mod the count).
inline void partnerDrives(const std::vector<int>& present, int own, int k, uint64_t offset,
                          std::vector<int>& out) {
  out.clear();
  for (int d : present)
    if (d != own) out.push_back(d);
  const int m = int(out.size());
  if (k > 0 && m > k) {
    std::vector<int> chosen(k);
    for (int t = 0; t < k; ++t) chosen[t] = out[(offset + uint64_t(t) * m / k) % m];
    out.swap(chosen);
  }
  out.push_back(own);
  std::sort(out.begin(), out.end());
}

}  // namespace mapfuse::aggregate::detail
