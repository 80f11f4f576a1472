/// @file `evaluate voxels`: per-class accuracy and IoU (eq. 10-11, Jeong et al. 2018) of a
/// semantic voxel map or of per-scan .label predictions against the labelled scans of a drive
/// (docs/lidar-ground-truth.md). Prints the Table 1 layout (Markdown) on stdout.
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "mapfuse/cli/app.hpp"
#include "mapfuse/stages/evaluate_voxels.hpp"

namespace {

using namespace mapfuse;

using VoxelsCommandState =
    apps::StageCommandState<stages::EvaluateVoxelsParams, stages::EvaluateVoxelsInputs>;

apps::CommandAction setupVoxels(CLI::App& sub) {
  auto st = std::make_shared<VoxelsCommandState>();
  sub.add_option("--drive", st->inputs.drive,
                 "KITTI raw drive folder with labels/<frame>.label ground truth")
      ->required();
  auto* map = sub.add_option("--map", st->inputs.map, "semantic voxel map (.ply) to score");
  auto* pred = sub.add_option("--predicted-labels", st->inputs.predicted_labels,
                              "folder of per-scan <frame>.label predictions to score");
  map->excludes(pred);
  return apps::stageCommand(
      sub, st, "output folder (voxels.json, voxels.md)", [](VoxelsCommandState& state) {
        const auto doc = stages::runEvaluateVoxels(state.inputs, state.out_dir, state.params);
        std::cout << doc["markdown"].get<std::string>();
      });
}

}  // namespace

MAPFUSE_EVALUATE_COMMAND(kVoxelsCommand, "voxels",
                         "per-class accuracy / IoU of a semantic voxel map or per-scan labels "
                         "(Jeong et al. 2018, eq. 10-11, Table 1 layout)",
                         setupVoxels);
