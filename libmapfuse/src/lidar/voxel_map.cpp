#include "mapfuse/lidar/voxel_map.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "mapfuse/core/error.hpp"

namespace mapfuse::lidar {
namespace {
constexpr int64_t kKeyBias = int64_t{1} << 20;
constexpr uint64_t kAxisMask = (uint64_t{1} << 21) - 1;
constexpr double kMaxLoad = 0.7;

inline uint64_t hashKey(uint64_t k) {
  k ^= k >> 33;
  k *= 0xff51afd7ed558ccdull;
  k ^= k >> 33;
  return k;
}
}  // namespace

uint64_t packKey(const VoxelCoord& c) {
  const int64_t x = int64_t{c.x} + kKeyBias, y = int64_t{c.y} + kKeyBias,
                z = int64_t{c.z} + kKeyBias;
  if (x < 0 || y < 0 || z < 0 || x > int64_t(kAxisMask) || y > int64_t(kAxisMask) ||
      z > int64_t(kAxisMask))
    throw InputError(
        "voxel coordinate out of range (±2^20 voxels): a point is too far from "
        "the map origin");
  return (uint64_t(x) << 42) | (uint64_t(y) << 21) | uint64_t(z);
}

VoxelCoord unpackKey(uint64_t key) {
  return {static_cast<int32_t>(int64_t((key >> 42) & kAxisMask) - kKeyBias),
          static_cast<int32_t>(int64_t((key >> 21) & kAxisMask) - kKeyBias),
          static_cast<int32_t>(int64_t(key & kAxisMask) - kKeyBias)};
}

SemanticVoxelMap::SemanticVoxelMap(double voxel_size, float min_log_prob)
    : voxel_size_(voxel_size), inv_voxel_size_(1.0 / voxel_size), min_log_prob_(min_log_prob) {
  if (!(voxel_size > 0)) throw InputError("voxel size must be > 0");
  if (!(min_log_prob < 0)) throw InputError("min_log_prob must be < 0");
  rehash(1024);
}

VoxelCoord SemanticVoxelMap::coordOf(const Eigen::Vector3d& p) const {
  return {static_cast<int32_t>(std::floor(p.x() * inv_voxel_size_)),
          static_cast<int32_t>(std::floor(p.y() * inv_voxel_size_)),
          static_cast<int32_t>(std::floor(p.z() * inv_voxel_size_))};
}

Eigen::Vector3d SemanticVoxelMap::center(uint64_t key) const {
  const VoxelCoord c = unpackKey(key);
  return Eigen::Vector3d(c.x + 0.5, c.y + 0.5, c.z + 0.5) * voxel_size_;
}

int64_t SemanticVoxelMap::find(uint64_t key) const {
  for (uint64_t s = hashKey(key) & mask_;; s = (s + 1) & mask_) {
    const uint32_t v = table_[s];
    if (v == 0) return -1;
    if (voxels_[v - 1].key == key) return v - 1;
  }
}

std::size_t SemanticVoxelMap::findOrInsert(uint64_t key) {
  uint64_t s = hashKey(key) & mask_;
  for (;; s = (s + 1) & mask_) {
    const uint32_t v = table_[s];
    if (v == 0) break;
    if (voxels_[v - 1].key == key) return v - 1;
  }
  Voxel vx{};
  vx.key = key;
  const float uniform = -std::log(static_cast<float>(kNumLidarClasses));
  std::fill(std::begin(vx.log_prob), std::end(vx.log_prob), uniform);
  vx.observations = 0;
  vx.label = 0;
  voxels_.push_back(vx);
  table_[s] = static_cast<uint32_t>(voxels_.size());
  if (static_cast<double>(voxels_.size()) > kMaxLoad * static_cast<double>(table_.size()))
    rehash(table_.size() * 2);
  return voxels_.size() - 1;
}

void SemanticVoxelMap::insertVoxel(const Voxel& v) {
  const std::size_t i = findOrInsert(v.key);
  voxels_[i] = v;
}

void SemanticVoxelMap::fuse(std::size_t index, const ClassDistribution& measurement) {
  Voxel& v = voxels_[index];
  float lp[kNumLidarClasses];
  float max_lp = -1e30f;
  for (int c = 0; c < kNumLidarClasses; ++c) {
    lp[c] = v.log_prob[c] + std::log(std::max(measurement[c], 1e-30f));  // eq. (5)
    max_lp = std::max(max_lp, lp[c]);
  }
  float sum = 0.f;
  for (int c = 0; c < kNumLidarClasses; ++c) sum += std::exp(lp[c] - max_lp);
  const float log_eta = max_lp + std::log(sum);  // eq. (6): normaliser
  int best = 0;
  for (int c = 0; c < kNumLidarClasses; ++c) {
    v.log_prob[c] = std::max(lp[c] - log_eta, min_log_prob_);
    if (v.log_prob[c] > v.log_prob[best]) best = c;
  }
  v.label = static_cast<uint8_t>(best);
  ++v.observations;
}

float SemanticVoxelMap::confidence(std::size_t index) const {
  const Voxel& v = voxels_[index];
  return std::exp(v.log_prob[v.label]);
}

void SemanticVoxelMap::filter(const std::vector<uint8_t>& keep) {
  if (keep.size() != voxels_.size()) throw InputError("filter mask size mismatch");
  std::size_t out = 0;
  for (std::size_t i = 0; i < voxels_.size(); ++i)
    if (keep[i]) voxels_[out++] = voxels_[i];
  voxels_.truncate(out);
  std::size_t cap = 1024;
  while (static_cast<double>(out) > kMaxLoad * static_cast<double>(cap)) cap *= 2;
  rehash(cap);
}

void SemanticVoxelMap::reserve(std::size_t n) {
  voxels_.reserve(n);
  std::size_t cap = table_.size();
  while (static_cast<double>(n) > kMaxLoad * static_cast<double>(cap)) cap *= 2;
  if (cap != table_.size()) rehash(cap);
}

std::size_t SemanticVoxelMap::memoryBytes() const {
  return voxels_.capacity() * sizeof(Voxel) + table_.capacity() * sizeof(uint32_t);
}

void SemanticVoxelMap::rehash(std::size_t capacity) {
  // The index is rebuilt from the voxel keys: free the old table first so that the two never
  // coexist at the memory peak.
  std::vector<uint32_t>().swap(table_);
  table_.assign(capacity, 0);
  mask_ = capacity - 1;
  for (std::size_t i = 0; i < voxels_.size(); ++i) {
    uint64_t s = hashKey(voxels_[i].key) & mask_;
    while (table_[s] != 0) s = (s + 1) & mask_;
    table_[s] = static_cast<uint32_t>(i + 1);
  }
}

}  // namespace mapfuse::lidar
