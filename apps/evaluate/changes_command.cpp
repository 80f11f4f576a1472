/// @file `evaluate changes`: a detected change report scored against the true changes of the
/// same before map (precision, recall, F1 per kind and class; false removals). Prints the
/// Markdown table on stdout. docs/evaluate.md "evaluate changes".
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "mapfuse/cli/app.hpp"
#include "mapfuse/stages/evaluate_changes.hpp"

namespace {

using namespace mapfuse;

using ChangesCommandState =
    apps::StageCommandState<stages::EvaluateChangesParams, stages::EvaluateChangesInputs>;

apps::CommandAction setupChanges(CLI::App& sub) {
  auto st = std::make_shared<ChangesCommandState>();
  sub.add_option("--detected", st->inputs.detected,
                 "detected changes (mapfuse.map_changes .json/.cbor), e.g. a map update's report")
      ->required();
  sub.add_option("--truth", st->inputs.truth,
                 "true changes (mapfuse.map_changes), e.g. simulate's truth/changes.json")
      ->required();
  sub.add_option("--before", st->inputs.before,
                 "the before map (mapfuse.vector_map), e.g. simulate's truth/vector_map.json "
                 "of the run without changes")
      ->required();
  return apps::stageCommand(sub, st, "output folder (change-scores.json, change-scores.md)",
                            [](ChangesCommandState& state) {
                              const auto doc = stages::runEvaluateChanges(
                                  state.inputs, state.out_dir, state.params);
                              std::cout << doc["markdown"].get<std::string>();
                            });
}

}  // namespace

MAPFUSE_EVALUATE_COMMAND(kChangesCommand, "changes",
                         "precision / recall / F1 of detected map changes against the true "
                         "ones, per change kind and class; false removals of unchanged elements",
                         setupChanges);
