#pragma once
/// @file One random forest (OpenCV ml::RTrees) per LiDAR label that judges whether a cluster
/// carrying that label is labelled correctly (Jeong et al. 2018, §2.1.2 error minimisation).
/// Stored as `<dir>/rtrees_<label name>.yml`; labels without a file are not filtered. A cluster
/// is dropped when the share of trees voting "correct" is below the label's threshold
/// (`<dir>/thresholds.json`, chosen on a validation drive by lidar/forest_thresholds.hpp;
/// 0.5, the forest's majority vote, without the file).
#include <array>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "mapfuse/core/classes.hpp"
#include "mapfuse/core/param.hpp"
#include "mapfuse/lidar/cluster_features.hpp"

namespace mapfuse::lidar {

struct RTreesSettings {
  int max_depth = 12;             ///< tree depth
  int min_sample_count = 5;       ///< samples per leaf
  int num_trees = 100;            ///< forest size
  int min_samples_per_class = 5;  ///< a label needs this many correct and wrong clusters
  uint64_t seed = 42;             ///< OpenCV RNG seed (deterministic training)
  bool balanced = false;  ///< class priors so that correct and wrong clusters weigh the same
  double min_validation_gain = 0.001;  ///< worst-drive validation IoU gain (0-1) to use a forest
  double gain_tolerance = 0.005;  ///< lowest threshold within this of the best worst gain (0-1)

  /// The training parameters of lidar-semantic-map.
  template <class V>
  void visit(V& v) {
    using namespace param;
    v("rtrees_max_depth", max_depth, "", "train: tree depth", in(1, 64));
    v("rtrees_trees", num_trees, "", "train: trees per forest", in(1, 10000));
    v("rtrees_min_sample_count", min_sample_count, "", "train: samples a tree node needs to split",
      in(1, 1e9));
    v("rtrees_min_samples", min_samples_per_class, "",
      "train: correct and wrong clusters a label needs", in(1, 1e9));
    v("seed", seed, "", "train: random seed", in(0, 4294967295.0));
    v("rtrees_balanced", balanced, "",
      "train: weigh correct and wrong clusters of a label equally (class priors)");
    v("forest_min_gain", min_validation_gain, "",
      "train: IoU (0-1) a label's forest must add on every validation drive, else it is not used",
      in(0, 1));
    v("forest_gain_tolerance", gain_tolerance, "",
      "train: the lowest threshold whose worst-drive IoU gain is within this (0-1) of the best "
      "is used (fewer clusters dropped for the same gain)",
      in(0, 1));
  }
};

/// Training samples of one label: features and whether the cluster's label was correct.
struct LabelSamples {
  std::vector<ClusterFeatures> features;
  std::vector<int> correct;         ///< 1 correct, 0 wrong (majority of the true labels)
  std::vector<int> points;          ///< points in the cluster
  std::vector<int> correct_points;  ///< of which truly of this label
  std::size_t truth_points = 0;     ///< projected points truly of this label (all clusters)
};

/// What training did per label.
struct TrainingReport {
  std::array<int, kNumLidarClasses> positives{}, negatives{};
  std::array<bool, kNumLidarClasses> trained{};
  std::array<double, kNumLidarClasses> training_accuracy{};  ///< on the training samples
};

class ClusterClassifier {
 public:
  ClusterClassifier();
  ~ClusterClassifier();
  ClusterClassifier(ClusterClassifier&&) noexcept;
  ClusterClassifier& operator=(ClusterClassifier&&) noexcept;

  /// @brief Loads every `rtrees_<label>.yml` found in `dir` (none found = empty classifier) and
  /// the thresholds of `thresholds.json` when present.
  /// @throws IoError when `dir` is not a folder; ParseError when a file cannot be loaded.
  static ClusterClassifier load(const std::filesystem::path& dir);

  /// @brief Trains one forest per label with enough positive and negative samples.
  static ClusterClassifier train(const std::array<LabelSamples, kNumLidarClasses>& samples,
                                 const RTreesSettings& settings, TrainingReport* report);

  /// @brief Writes `rtrees_<label>.yml` for every trained label and `thresholds.json` (each
  /// file atomically).
  void save(const std::filesystem::path& dir) const;

  bool empty() const;
  bool has(LidarClass label) const;
  /// @brief Names of the labels that have a forest.
  std::vector<std::string> labels() const;

  /// @brief True when the cluster is judged correctly labelled: its share of "correct" votes
  /// is at least the label's threshold (always true without a forest).
  bool accept(LidarClass label, const ClusterFeatures& features) const;

  /// @brief Share of the label's trees (0-1) voting that the cluster is correctly labelled
  /// (1 without a forest).
  float correctVotes(LidarClass label, const ClusterFeatures& features) const;

  /// @brief Minimum share of "correct" votes below which a cluster of `label` is dropped.
  float threshold(LidarClass label) const;
  void setThreshold(LidarClass label, float min_correct_votes);
  /// @brief Forgets the label's forest: its clusters are no longer filtered.
  void remove(LidarClass label);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mapfuse::lidar
