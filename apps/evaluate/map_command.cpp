/// @file `evaluate map`: vector map(s) against the ground-truth map (§5, Song et al. 2023),
/// optionally trajectories of aligned LSMs. Prints per-class relative precision on stdout.
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "mapfuse/cli/app.hpp"
#include "mapfuse/stages/evaluate_map.hpp"

namespace {

using namespace mapfuse;

struct MapCommandState
    : apps::StageCommandState<stages::EvaluateMapParams, stages::EvaluateMapInputs> {
  std::vector<std::string> lsm_args;  ///< --lsm as given (lists expanded when the action runs)
};

apps::CommandAction setupMap(CLI::App& sub) {
  auto st = std::make_shared<MapCommandState>();
  sub.add_option("--map", st->inputs.maps,
                 "vector map(s) to evaluate (.json/.cbor); several maps -> error vs traversals")
      ->required();
  sub.add_option("--truth", st->inputs.truth, "ground-truth vector map")->required();
  sub.add_option("--lsm", st->lsm_args,
                 "aligned LSMs for trajectory metrics; @list.txt or - (stdin) for lists");
  sub.add_option("--truth-trajectories", st->inputs.truth_trajectories,
                 "folder of <drive>.trajectory.json (simulate truth/), needed with --lsm");
  sub.add_option("--traversals", st->inputs.traversals,
                 "traversals per --map (default: from aggregate.summary.json beside each map)");
  return apps::stageCommand(sub, st, "output folder", [](MapCommandState& state) {
    state.inputs.lsms = cli::expandInputList(state.lsm_args);
    const auto run = stages::runEvaluateMap(state.inputs, state.out_dir, state.params);
    const nlohmann::json summary = stages::toJson(run);
    nlohmann::json brief = nlohmann::json::array();
    for (const auto& m : summary["maps"]) {
      nlohmann::json classes = nlohmann::json::object();
      for (const auto& c : m["classes"])
        classes[c["class"].get<std::string>()] = {
            {"relative_precision_m", c["relative_precision_m"]},
            {"completeness", c["completeness"]},
            {"redundancy", c["redundancy"]}};
      brief.push_back({{"map", m["map"]}, {"traversals", m["traversals"]}, {"classes", classes}});
    }
    std::cout << brief.dump() << "\n";
  });
}

MAPFUSE_EVALUATE_COMMAND(kMapCommand, "map",
                         "vector map(s) against the ground-truth map: relative precision, "
                         "absolute error, completeness, redundancy (+ ATE/RPE with --lsm)",
                         setupMap);

}  // namespace
