#pragma once
/// @file What `evaluate voxels` can know makes its scores meaningless (docs/evaluate.md "Inputs
/// that cannot be scored"): an empty truth (no labelled truth voxel or point), an empty map, or
/// a map none of whose voxels meets a truth voxel (another frame or pose source). Each problem
/// is one sentence naming the file or folder; eval::warnOrRefuse reports them.
#include <string>
#include <vector>

#include "mapfuse/eval/voxel_metrics.hpp"
#include "mapfuse/eval/voxel_truth.hpp"

namespace mapfuse::eval {

/// @brief Problems of a voxel map (`map_file`) scored against the truth of `truth_dir`.
std::vector<std::string> voxelMapProblems(const MapComparison& cmp, const std::string& map_file,
                                          const std::string& truth_dir);

/// @brief Problems of per-scan predictions scored against the truth labels of `truth_dir`.
std::vector<std::string> scanLabelProblems(const LabelScores& scores, const std::string& truth_dir);

/// @brief Why a mean score of `scores` is undefined (null in the summary), or empty.
std::string undefinedScoreReason(const LabelScores& scores);

}  // namespace mapfuse::eval
