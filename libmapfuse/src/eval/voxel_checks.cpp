#include "mapfuse/eval/voxel_checks.hpp"

#include <cmath>

namespace mapfuse::eval {

std::vector<std::string> voxelMapProblems(const MapComparison& cmp, const std::string& map_file,
                                          const std::string& truth_dir) {
  std::vector<std::string> problems;
  if (cmp.truth_voxels == 0)
    problems.push_back(truth_dir +
                       "/labels: the truth holds no labelled static voxel in range: nothing "
                       "to score");
  if (cmp.map_voxels == 0) problems.push_back(map_file + ": the map holds no voxel");
  if (cmp.truth_voxels > 0 && cmp.map_voxels > 0 && cmp.unmatched == cmp.map_voxels)
    problems.push_back(map_file + " and the truth of " + truth_dir +
                       " do not overlap (no map voxel holds a truth point): another frame or "
                       "pose source?");
  return problems;
}

std::vector<std::string> scanLabelProblems(const LabelScores& scores,
                                           const std::string& truth_dir) {
  if (scores.evaluated > 0) return {};
  return {truth_dir + "/labels: no truth point carries a scored class: nothing to score"};
}

std::string undefinedScoreReason(const LabelScores& scores) {
  if (!std::isnan(scores.mean_iou) && !std::isnan(scores.mean_accuracy)) return "";
  if (scores.evaluated == 0) return "no truth item was scored (empty truth)";
  return "no class has a prediction or a truth item (empty map and truth)";
}

}  // namespace mapfuse::eval
