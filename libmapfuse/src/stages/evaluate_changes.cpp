#include "mapfuse/stages/evaluate_changes.hpp"

#include "mapfuse/core/log.hpp"
#include "mapfuse/eval/change_report.hpp"
#include "mapfuse/eval/input_problems.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/map_changes_io.hpp"
#include "mapfuse/io/output_transaction.hpp"
#include "mapfuse/io/stage_report.hpp"
#include "mapfuse/io/vector_map_io.hpp"

namespace mapfuse::stages {

nlohmann::json runEvaluateChanges(const EvaluateChangesInputs& in, const std::filesystem::path& out,
                                  const EvaluateChangesParams& P) {
  constexpr const char* kStage = "evaluate-changes";
  validateParams(P);
  io::OutputTransaction outputs(out);  // locked and writable before the work (exit 4)
  const MapChanges detected = io::readMapChanges(in.detected);
  const MapChanges truth = io::readMapChanges(in.truth);
  const VectorMap before = io::readVectorMap(in.before);
  eval::checkAgainstBefore(detected, in.detected.string(), before, in.before.string());
  eval::checkAgainstBefore(truth, in.truth.string(), before, in.before.string());
  const eval::ChangeScores scores = eval::scoreChanges(detected, truth, before, P.score);

  std::vector<std::string> noted;
  eval::warnOrRefuse(eval::changeInputProblems(scores, in.truth.string()), P.strict,
                     "evaluate changes", noted);
  nlohmann::json doc = eval::changeScoresToJson(scores, P.score);
  if (!doc["false_removals"]["within_bound"].get<bool>())
    MAPFUSE_WARN("evaluate changes: " << scores.false_removals << " false removals of "
                                      << scores.unchanged_elements
                                      << " unchanged elements exceed max_false_removal_rate "
                                      << P.score.max_false_removal_rate);
  doc["problems"] = noted;
  const std::string md = eval::changeScoresToMarkdown(scores, P.score, P.title);
  io::writeDocument(out / "change-scores.json", doc);
  io::writeBytesAtomic(out / "change-scores.md", md);
  io::writeResolvedConfig(out, kStage, paramsToJson(P));
  io::writeSummary(out, kStage,
                   {{"detected_changes", detected.changes.size()},
                    {"true_changes", truth.changes.size()},
                    {"precision", doc["overall"]["precision"]},
                    {"recall", doc["overall"]["recall"]},
                    {"f1", doc["overall"]["f1"]},
                    {"f1_by_kind",
                     [&] {
                       nlohmann::json j;
                       for (const auto& [k, v] : doc["by_kind"].items()) j[k] = v["f1"];
                       return j;
                     }()},
                    {"false_removals", doc["false_removals"]},
                    {"problems", noted}});
  outputs.commit();
  doc["markdown"] = md;
  return doc;
}

}  // namespace mapfuse::stages
