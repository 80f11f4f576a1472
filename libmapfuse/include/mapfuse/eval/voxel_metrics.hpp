#pragma once
/// @file Semantic labelling scores of Jeong et al. 2018: per-class accuracy = TP / (TP + FP)
/// (eq. 10) and IoU = TP / (TP + FP + FN) (eq. 11) over the classes of the paper's Table 1
/// (road, sidewalk, building, fence, pole, vegetation, vehicle), from a confusion matrix.
#include <array>
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "mapfuse/core/classes.hpp"

namespace mapfuse::eval {

/// The columns of Table 1, in order.
constexpr std::array<LidarClass, 7> kTable1Classes = {
    LidarClass::kRoad, LidarClass::kSidewalk,   LidarClass::kBuilding, LidarClass::kFence,
    LidarClass::kPole, LidarClass::kVegetation, LidarClass::kVehicle};

/// Counts of (truth, prediction) pairs. Truth `unlabeled` is ignored by the scores;
/// prediction `unlabeled` (or a missing prediction) is a false negative of the true class.
/// Spurious predictions (where the truth says nothing should be, e.g. a moving car's trace)
/// are false positives of the predicted class only.
struct ConfusionMatrix {
  std::array<std::array<uint64_t, kNumLidarClasses>, kNumLidarClasses> counts{};  ///< [truth][pred]
  std::array<uint64_t, kNumLidarClasses> spurious{};  ///< predictions where nothing should be

  void add(LidarClass truth, LidarClass pred, uint64_t n = 1) {
    counts[static_cast<int>(truth)][static_cast<int>(pred)] += n;
  }
  void addSpurious(LidarClass pred, uint64_t n = 1) { spurious[static_cast<int>(pred)] += n; }
  ConfusionMatrix& operator+=(const ConfusionMatrix& o);
};

/// Scores of one class.
struct ClassScore {
  LidarClass cls = LidarClass::kUnlabeled;
  uint64_t tp = 0, fp = 0, fn = 0;
  double accuracy = 0.0;  ///< eq. (10); NaN when TP + FP = 0
  double iou = 0.0;       ///< eq. (11); NaN when TP + FP + FN = 0
};

/// Scores over the Table 1 classes.
struct LabelScores {
  std::array<ClassScore, kTable1Classes.size()> classes;
  double mean_accuracy = 0.0;  ///< mean over classes with a defined accuracy
  double mean_iou = 0.0;       ///< mean over classes with a defined IoU
  uint64_t evaluated = 0;      ///< truth-labelled items counted
};

/// @brief eq. (10)-(11) from a confusion matrix.
LabelScores scoreConfusion(const ConfusionMatrix& m);

/// @brief JSON: {"classes": {"road": {"tp","fp","fn","accuracy","iou"}, ...}, "mean_accuracy",
/// "mean_iou", "evaluated"} (undefined scores are null).
nlohmann::json scoresToJson(const LabelScores& s);

/// @brief Markdown table in the paper's Table 1 layout: a header row of the classes plus
/// "mean", then rows "Accuracy (%)" and "IoU (%)" (one decimal, "-" when undefined).
/// @param title first column header (e.g. the method name)
std::string scoresToMarkdown(const LabelScores& s, const std::string& title);

}  // namespace mapfuse::eval
