#pragma once
/// @file Stage `evaluate changes` (docs/evaluate.md "evaluate changes"): a detected change
/// report (mapfuse.map_changes, e.g. a map update's) scored against the true changes (simulate's
/// truth/changes.json) of the same before map: precision, recall and F1 overall, per change kind
/// and per class, and the false removals of unchanged elements. Writes change-scores.json,
/// change-scores.md and evaluate-changes.{config,summary}.json in the output folder.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "mapfuse/cli/params.hpp"
#include "mapfuse/eval/change_metrics.hpp"

namespace mapfuse::stages {

struct EvaluateChangesParams {
  static constexpr const char* kName = "EvaluateChangesParams";
  eval::ChangeScoreSettings score;
  std::string title = "mapfuse";  ///< first column of the Markdown table
  bool strict = false;            ///< refuse (exit 3) inputs that leave the scores undefined

  template <class V>
  void visit(V& v) {
    score.visit(v);
    v("title", title, "", "method name in the first column of the Markdown table");
    v("strict", strict, "",
      "refuse (exit 3) a truth without changes or a before map whose every element changed "
      "(default: a warning and a 'problems' list in the summary)");
  }
};

struct EvaluateChangesInputs {
  std::filesystem::path detected;  ///< detected changes (mapfuse.map_changes)
  std::filesystem::path truth;     ///< true changes (mapfuse.map_changes)
  std::filesystem::path before;    ///< the before map (mapfuse.vector_map): its unchanged elements
};

/// @brief Scores the detected changes and writes the reports into `out`. Returns the
/// change-scores.json document plus "markdown".
/// @throws IoError (missing file, exit 4), ParseError (malformed file, or a before_id not in the
/// before map / of another class, exit 3), InputError (origins differ; with strict, undefined
/// scores; exit 3).
nlohmann::json runEvaluateChanges(const EvaluateChangesInputs& in, const std::filesystem::path& out,
                                  const EvaluateChangesParams& params);

}  // namespace mapfuse::stages
