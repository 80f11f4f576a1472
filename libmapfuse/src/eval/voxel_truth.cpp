#include "mapfuse/eval/voxel_truth.hpp"

#include <cmath>
#include <string>
#include <unordered_set>

#include "mapfuse/core/error.hpp"

namespace mapfuse::eval {
namespace {
constexpr int kBits = 21;
constexpr int64_t kOffset = int64_t(1) << (kBits - 1);
constexpr uint64_t kMask = (uint64_t(1) << kBits) - 1;
}  // namespace

VoxelTruth::VoxelTruth(double voxel_size) : size_(voxel_size) {
  if (!(voxel_size > 0.0)) throw InputError("truth voxel size must be positive");
}

uint64_t VoxelTruth::keyOf(const Eigen::Vector3d& p) const {
  uint64_t key = 0;
  for (int a = 0; a < 3; ++a) {
    const int64_t c = static_cast<int64_t>(std::floor(p[a] / size_)) + kOffset;
    if (c < 0 || c > static_cast<int64_t>(kMask))
      throw InputError("point " + std::to_string(p[a]) + " m is outside the voxel key range");
    key |= (static_cast<uint64_t>(c) & kMask) << (kBits * a);
  }
  return key;
}

void VoxelTruth::addPoint(const Eigen::Vector3d& p_map, uint32_t word) {
  const uint16_t id = static_cast<uint16_t>(word & 0xFFFF);
  Counts& c = voxels_[keyOf(p_map)];
  ++c[static_cast<int>(lidarClassFromSemanticKitti(id))];
  if (isMovingKittiId(id)) ++c[kNumLidarClasses];
}

std::optional<VoxelTruth::Label> VoxelTruth::at(uint64_t key) const {
  const auto it = voxels_.find(key);
  if (it == voxels_.end()) return std::nullopt;
  const Counts& c = it->second;
  Label l;
  uint32_t best = 0, total = 0;
  for (int k = 0; k < kNumLidarClasses; ++k) {
    total += c[k];
    if (c[k] > best) best = c[k], l.cls = static_cast<LidarClass>(k);  // ties: lower class id
  }
  l.moving = 2 * c[kNumLidarClasses] > total;
  return l;
}

std::vector<std::pair<uint64_t, VoxelTruth::Label>> VoxelTruth::all() const {
  std::vector<std::pair<uint64_t, Label>> out;
  out.reserve(voxels_.size());
  for (const auto& kv : voxels_) out.emplace_back(kv.first, *at(kv.first));
  return out;
}

MapComparison compareVoxelMap(const LabeledCloud& map, const VoxelTruth& truth) {
  if (map.labels.size() != map.points.size())
    throw InputError("voxel map: " + std::to_string(map.points.size()) + " points but " +
                     std::to_string(map.labels.size()) + " labels");
  MapComparison r;
  r.map_voxels = map.size();
  std::unordered_map<uint64_t, uint8_t> predicted;
  predicted.reserve(map.size());
  for (std::size_t i = 0; i < map.size(); ++i)
    predicted[truth.keyOf(map.points[i].cast<double>())] = map.labels[i];
  std::unordered_set<uint64_t> matched;
  for (const auto& [key, label] : truth.all()) {
    const auto it = predicted.find(key);
    const bool present = it != predicted.end();
    if (present) matched.insert(key);
    if (label.moving) {
      ++r.moving_truth;
      if (present) {
        ++r.moving_in_map;
        r.confusion.addSpurious(static_cast<LidarClass>(it->second));
      }
      continue;
    }
    if (label.cls == LidarClass::kUnlabeled) continue;
    ++r.truth_voxels;
    if (label.cls == LidarClass::kVehicle) {
      ++r.parked_truth;
      r.parked_in_map += present;
    }
    r.confusion.add(label.cls,
                    present ? static_cast<LidarClass>(it->second) : LidarClass::kUnlabeled);
  }
  r.unmatched = predicted.size() - matched.size();
  return r;
}

ConfusionMatrix compareScanLabels(const std::vector<uint32_t>& predicted,
                                  const std::vector<uint32_t>& truth) {
  if (predicted.size() != truth.size())
    throw InputError("scan labels: " + std::to_string(predicted.size()) + " predictions but " +
                     std::to_string(truth.size()) + " truth labels");
  ConfusionMatrix m;
  for (std::size_t i = 0; i < truth.size(); ++i)
    m.add(lidarClassFromSemanticKitti(static_cast<uint16_t>(truth[i] & 0xFFFF)),
          lidarClassFromSemanticKitti(static_cast<uint16_t>(predicted[i] & 0xFFFF)));
  return m;
}

void addLabelledScan(VoxelTruth& truth, const std::vector<Eigen::Vector3f>& points_velo,
                     const std::vector<uint32_t>& labels, const Pose3& T_map_velo, double min_range,
                     double max_range, const Eigen::Matrix<double, 3, 4>* velo_to_image, int width,
                     int height) {
  if (points_velo.size() != labels.size())
    throw InputError("labelled scan: " + std::to_string(points_velo.size()) + " points but " +
                     std::to_string(labels.size()) + " labels");
  for (std::size_t i = 0; i < points_velo.size(); ++i) {
    const Eigen::Vector3d p = points_velo[i].cast<double>();
    const double r = p.norm();
    if (r < min_range || r > max_range) continue;
    if (velo_to_image) {
      const Eigen::Vector3d q = *velo_to_image * p.homogeneous();
      if (q.z() <= 0.0) continue;
      const long u = std::lround(q.x() / q.z()), v = std::lround(q.y() / q.z());
      if (u < 0 || v < 0 || u >= width || v >= height) continue;
    }
    truth.addPoint(T_map_velo * p, labels[i]);
  }
}

}  // namespace mapfuse::eval
