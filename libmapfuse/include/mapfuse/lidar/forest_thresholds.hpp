#pragma once
/// @file The per-label rule that decides how, and whether, a label's forest filters clusters
/// (error minimisation, Jeong et al. 2018 §2.1.2). On validation drives that are neither
/// training nor test drives, each threshold t on the share of trees voting "correct" (clusters
/// below t are dropped) is scored by its worst gain over the drives, min_d IoU_d(t) - IoU_d(off),
/// of the label's point IoU; the lowest threshold whose worst gain is within a tolerance of the
/// best worst gain is chosen (on a plateau, the one that drops the fewest clusters), and the
/// forest is used only when its worst gain is at least a minimum gain. A forest that helps on one
/// drive but erases the label on another (fence, issue 24) is therefore not used at that threshold.
#include <cstddef>
#include <string>
#include <vector>

#include "mapfuse/lidar/cluster_classifier.hpp"

namespace mapfuse::lidar {

/// One validation drive's clusters of a label and the forest's votes on them.
struct ValidationSet {
  LabelSamples samples;
  std::vector<float> correct_votes;  ///< share of trees (0-1) voting "correct", per cluster
};

/// What the rule chose for one label, with the validation figures behind it.
struct ThresholdChoice {
  bool validated = false;         ///< some validation drive has true points of this label
  bool used = false;              ///< the forest filters this label
  float min_correct_votes = 0.5;  ///< share of trees (0-1); clusters below it are dropped
  double worst_gain = 0;          ///< min over drives of the IoU gain (0-1) at the choice
  double iou_unfiltered = 0;      ///< IoU (0-1) over all validation drives, no filtering
  double iou_filtered = 0;        ///< at min_correct_votes (= iou_unfiltered when not used)
  double iou_majority = 0;        ///< at 0.5, the forest's majority vote (the rule before)
  std::vector<double> worst_gain_by_threshold;  ///< at thresholds 0.05, 0.10, ..., 0.95
  std::size_t clusters = 0;                     ///< validation clusters of the label
  std::size_t rejected_clusters = 0;            ///< at min_correct_votes
  std::size_t rejected_correct_points = 0;      ///< truly of the label, lost
  std::size_t rejected_wrong_points = 0;        ///< of another class, removed
  std::string reason;                           ///< why the forest is not used (empty when used)
};

/// @brief Point IoU of a label on validation clusters when every cluster whose share of
/// "correct" votes is below `min_correct_votes` is dropped:
/// IoU = TP / (truth + FP), TP = kept points truly of the label, FP = kept points of other
/// classes, truth = samples.truth_points (dropped or missed truth points are the FN).
double validationIou(const LabelSamples& samples, const std::vector<float>& correct_votes,
                     float min_correct_votes);

/// @brief The rule above on the thresholds 0.05, 0.10, ..., 0.95. Drives without true points of
/// the label do not vote.
/// @param min_gain worst-drive IoU gain (0-1) the forest must bring, else used = false
/// @param tolerance IoU (0-1): the lowest threshold with a worst gain >= best - tolerance wins
ThresholdChoice chooseThreshold(const std::vector<ValidationSet>& drives, double min_gain,
                                double tolerance = 0.0);

}  // namespace mapfuse::lidar
