#pragma once
/// @file The report of `evaluate changes` (docs/evaluate.md "evaluate changes"): the scores as
/// JSON (change-scores.json, the summary's figures), as a Markdown table (change-scores.md), and
/// the inputs that leave the scores undefined.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mapfuse/eval/change_metrics.hpp"

namespace mapfuse::eval {

/// @brief {"overall", "by_kind", "by_class": {tp, fp, fn, precision, recall, f1} (null when
/// undefined), "false_removals": {count, unchanged_elements, rate, bound, within_bound},
/// "false_other_changes", "added_match_distance_m", "missed", "wrong"}.
nlohmann::json changeScoresToJson(const ChangeScores& scores, const ChangeScoreSettings& settings);

/// @brief Markdown: one table (rows: all changes, each kind, each class with changes; columns
/// TP, FP, FN, precision, recall, F1 in %, one decimal, "-" when undefined) and the false
/// removals line.
std::string changeScoresToMarkdown(const ChangeScores& scores, const ChangeScoreSettings& settings,
                                   const std::string& title);

/// @brief Inputs that leave the scores undefined: a truth without changes (recall and F1), a
/// before map whose every element changed (false removal rate). One sentence each, naming the
/// file. (A detection without changes is a result: precision null, recall and F1 0.)
std::vector<std::string> changeInputProblems(const ChangeScores& scores,
                                             const std::string& truth_file);

}  // namespace mapfuse::eval
