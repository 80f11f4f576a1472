#include "sorted_voxel_keys.hpp"

#include <algorithm>

namespace mapfuse::lidar::detail {
namespace {
constexpr uint64_t kAxisMask = (uint64_t{1} << 21) - 1;  // packKey's field width
constexpr int kDigitBits = 11;
constexpr std::size_t kBuckets = std::size_t{1} << kDigitBits;

/// Bits needed for values 0..n-1.
int bitsFor(int64_t n) {
  int b = 0;
  while ((int64_t{1} << b) < n) ++b;
  return b;
}
}  // namespace

SortedVoxelKeys::SortedVoxelKeys(const SemanticVoxelMap& map) {
  const auto& vox = map.voxels();
  const std::size_t n = vox.size();
  if (n == 0) return;
  // Bounding box of the biased key fields (packKey is monotone in each coordinate).
  uint64_t lo[3] = {kAxisMask, kAxisMask, kAxisMask}, hi[3] = {0, 0, 0};
  for (const Voxel& v : vox)
    for (int a = 0; a < 3; ++a) {
      const uint64_t f = (v.key >> (42 - 21 * a)) & kAxisMask;
      lo[a] = std::min(lo[a], f);
      hi[a] = std::max(hi[a], f);
    }
  nx_ = int64_t(hi[0] - lo[0]) + 1;
  ny_ = int64_t(hi[1] - lo[1]) + 1;
  nz_ = int64_t(hi[2] - lo[2]) + 1;
  const int bz = bitsFor(nz_), by = bitsFor(ny_), bits = bitsFor(nx_) + by + bz;
  sy_ = bz;
  sx_ = by + bz;
  my_ = (uint64_t{1} << by) - 1;
  mz_ = (uint64_t{1} << bz) - 1;
  keys_.resize(n);
  index_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const uint64_t k = vox[i].key;
    keys_[i] = key(int64_t(((k >> 42) & kAxisMask) - lo[0]),
                   int64_t(((k >> 21) & kAxisMask) - lo[1]), int64_t((k & kAxisMask) - lo[2]));
    index_[i] = static_cast<uint32_t>(i);
  }
  // LSD radix sort, kDigitBits per pass (stable), skipping digits that never vary.
  std::vector<uint64_t> keys2(n);
  std::vector<uint32_t> index2(n);
  std::vector<std::size_t> count(kBuckets);
  for (int shift = 0; shift < bits; shift += kDigitBits) {
    std::fill(count.begin(), count.end(), 0);
    for (uint64_t k : keys_) ++count[(k >> shift) & (kBuckets - 1)];
    if (count[(keys_[0] >> shift) & (kBuckets - 1)] == n) continue;
    std::size_t sum = 0;
    for (auto& c : count) {
      const std::size_t c0 = c;
      c = sum;
      sum += c0;
    }
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t dst = count[(keys_[i] >> shift) & (kBuckets - 1)]++;
      keys2[dst] = keys_[i];
      index2[dst] = index_[i];
    }
    keys_.swap(keys2);
    index_.swap(index2);
  }
}

}  // namespace mapfuse::lidar::detail
