#pragma once
/// @file Ground truth for semantic voxel maps (docs/lidar-ground-truth.md): truth voxels built
/// from labelled scans (SemanticKITTI words: class = majority of the voxel's points, "moving"
/// when most points carry a moving id 252-259), and the comparison of a labelled voxel map or of
/// per-scan label predictions with it, as a confusion matrix for eq. (10)-(11).
#include <array>
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "mapfuse/core/labeled_cloud.hpp"
#include "mapfuse/core/param.hpp"
#include "mapfuse/core/se3.hpp"
#include "mapfuse/eval/voxel_metrics.hpp"

namespace mapfuse::eval {

/// @brief True when a SemanticKITTI id denotes a moving object (252-259).
inline bool isMovingKittiId(uint16_t id) {
  return id >= 252 && id <= 259;
}

/// Voxelised truth in the map frame.
class VoxelTruth {
 public:
  /// What one truth voxel is.
  struct Label {
    LidarClass cls = LidarClass::kUnlabeled;
    bool moving = false;
  };

  /// @param voxel_size m, must equal the evaluated map's voxel size.
  explicit VoxelTruth(double voxel_size);

  /// @brief Adds one labelled point (map frame).
  void addPoint(const Eigen::Vector3d& p_map, uint32_t word);
  /// @brief Key of the voxel containing p (floor(p / size), packed 21 bits per axis).
  uint64_t keyOf(const Eigen::Vector3d& p) const;
  /// @brief The truth at a key, nullopt when no labelled point fell there.
  std::optional<Label> at(uint64_t key) const;
  std::size_t size() const { return voxels_.size(); }
  double voxelSize() const { return size_; }
  /// @brief Every truth voxel's key and label (unordered).
  std::vector<std::pair<uint64_t, Label>> all() const;

 private:
  using Counts = std::array<uint32_t, kNumLidarClasses + 1>;  // classes + moving points
  double size_;
  std::unordered_map<uint64_t, Counts> voxels_;
};

/// Result of comparing a voxel map with the truth.
struct MapComparison {
  ConfusionMatrix confusion;
  uint64_t map_voxels = 0;     ///< voxels in the map
  uint64_t unmatched = 0;      ///< map voxels where no truth point fell (not scored)
  uint64_t truth_voxels = 0;   ///< static truth voxels (scored; missing ones are FN)
  uint64_t moving_truth = 0;   ///< truth voxels of moving cars
  uint64_t moving_in_map = 0;  ///< ... still present in the map (any label)
  uint64_t parked_truth = 0;   ///< static vehicle truth voxels
  uint64_t parked_in_map = 0;  ///< ... present in the map (any label)
};

/// @brief Scores a labelled voxel map (voxel centres, LidarClass labels) against the truth:
/// static truth voxels give (truth, predicted or unlabeled if absent) pairs; map voxels on moving
/// cars' truth voxels are spurious predictions (false positives of their class).
/// @throws InputError when the cloud's arrays differ in size.
MapComparison compareVoxelMap(const LabeledCloud& map, const VoxelTruth& truth);

/// @brief Per-point confusion of predicted vs true SemanticKITTI words of one scan; moving truth
/// points count as their static class (a per-scan label of a moving car is right as vehicle).
/// @throws InputError when the sizes differ.
ConfusionMatrix compareScanLabels(const std::vector<uint32_t>& predicted,
                                  const std::vector<uint32_t>& truth);

/// Which labelled points become truth voxels: the points the mapping pipeline can label.
struct VoxelTruthSettings {
  double voxel_size = 0.05;  ///< m, must equal the evaluated map's voxel size
  double min_range = 5.0;    ///< m, truth only from points at least this far from the Velodyne
  double max_range = 50.0;   ///< m, and at most this far
  bool camera_fov = true;    ///< truth only from points that land in image_02

  template <class V>
  void visit(V& v) {
    // Keys pack 21 bits per axis: 1 cm voxels still reach +-10 km from the first pose.
    v("voxel_size", voxel_size, "m", "voxel edge, equal to the evaluated map's",
      param::ge(0.01) & param::le(10));
    v("min_range", min_range, "m", "truth voxels only from points at least this far",
      param::ge(0) & param::le(1000));
    v("max_range", max_range, "m", "truth voxels only from points at most this far",
      param::gt(0) & param::le(1000));
    v.relation("min_range", min_range, min_range < max_range, "< max_range");
    v("camera_fov", camera_fov, "", "truth voxels only from points that land in image_02");
  }
};

/// @brief Adds the points of a labelled scan to the truth: p_map = T_map_velo * p_velo for the
/// points with range in [min_range, max_range] and, when `velo_to_image` is given, landing inside
/// a width x height image (the points the mapping pipeline can label).
void addLabelledScan(VoxelTruth& truth, const std::vector<Eigen::Vector3f>& points_velo,
                     const std::vector<uint32_t>& labels, const Pose3& T_map_velo, double min_range,
                     double max_range, const Eigen::Matrix<double, 3, 4>* velo_to_image, int width,
                     int height);

}  // namespace mapfuse::eval
