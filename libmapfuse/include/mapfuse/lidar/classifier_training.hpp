#pragma once
/// @file Training of the cluster classifiers (Jeong et al. 2018, §2.1.2): the clusters of every
/// frame with SemanticKITTI labels (labels/<frame>.label) are labelled from the image semantics
/// as in the map, and each is a correct sample of its label when the majority of its points'
/// true labels agrees, a wrong one otherwise; one forest per label (lidar/cluster_classifier.hpp).
#include <filesystem>
#include <string>
#include <vector>

#include "mapfuse/io/kitti_raw.hpp"
#include "mapfuse/lidar/cluster_classifier.hpp"
#include "mapfuse/lidar/forest_thresholds.hpp"
#include "mapfuse/lidar/semantic_mapper.hpp"

namespace mapfuse::lidar {

/// What one training drive gave.
struct TrainingDriveStats {
  std::string drive;  ///< folder
  std::size_t frames_used = 0, frames_without_labels = 0, clusters = 0;
  std::string semantics;  ///< "precomputed" or "enet"
};

struct ClassifierTrainingResult {
  ClusterClassifier classifier;
  TrainingReport report;
  std::vector<TrainingDriveStats> drives;
  std::size_t frames_used = 0;
  bool validated = false;                                      ///< validation drives were given
  std::vector<TrainingDriveStats> validation_drives;           ///< what each validation drive gave
  std::array<ThresholdChoice, kNumLidarClasses> thresholds{};  ///< per label (validated only)
};

/// @brief Trains the forests from the selected frames of labelled drives, with the semantics,
/// projection and clustering settings of the map; then, when `validation` drives are given,
/// chooses each label's threshold on them and drops the forests that do not raise their
/// label's validation IoU (lidar/forest_thresholds.hpp).
/// @param cache_root ENet outputs of a drive are cached in cache_root/<drive folder name>
/// (empty: no cache)
/// @throws InputError when no drive or no labelled frame is given; IoError when a drive has no
/// labels/ folder; ParseError when a label file does not match its scan.
ClassifierTrainingResult trainClusterClassifier(
    const std::vector<std::filesystem::path>& drives,
    const std::vector<std::filesystem::path>& validation, const io::FrameRange& frames,
    const SemanticMapSettings& map, const RTreesSettings& rtrees,
    const std::filesystem::path& cache_root);

}  // namespace mapfuse::lidar
