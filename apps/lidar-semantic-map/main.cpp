// lidar-semantic-map: KITTI raw drive -> semantic voxel map (Jeong et al. 2018; docs/lidar.md).
// `lidar-semantic-map DRIVE -o OUT` builds the map; `lidar-semantic-map train DRIVE... -o DIR`
// fits the per-label cluster classifiers from drives with labels/<frame>.label files.
#include "about.hpp"
#include "mapfuse/cli/app.hpp"
#include "mapfuse/stages/lidar_semantic_map.hpp"

static const char* const kDrive =
    "KITTI raw drive (<date>/<date>_drive_<name>_sync) or sequence (sequences/NN)";

namespace {
/// The `train` subcommand's inputs.
struct TrainArgs {
  CLI::App* sub = nullptr;
  std::string out;
  std::vector<std::string> drives, validation;
};

TrainArgs addTrain(CLI::App& app) {
  TrainArgs t;
  t.sub = app.add_subcommand("train", "Fit the per-label cluster classifiers");
  t.sub->add_option("drives", t.drives, "Labelled drives, @list.txt or -")->required();
  t.sub->add_option("-o,--out", t.out, "Classifier folder")->required();
  t.sub->add_option("--validation", t.validation,
                    "Labelled drives (not training, not test) on which each label's threshold is "
                    "chosen and forests that cost their label IoU are dropped");
  t.sub->fallthrough();
  return t;
}
}  // namespace

int main(int argc, char** argv) {
  using namespace mapfuse;
  cli::StageTool<stages::LidarSemanticMapParams> tool("lidar-semantic-map",
                                                      apps::about::kLidarSemanticMap);
  std::string drive, out;
  tool.app().add_option("drive", drive, kDrive);
  tool.app().add_option("-o,--out", out, "Output folder");
  TrainArgs train = addTrain(tool.app());
  return tool.run(argc, argv, [&](const stages::LidarSemanticMapParams& params) {
    if (train.sub->parsed()) {
      const auto list = cli::expandInputList(train.drives);
      const auto held = cli::expandInputList(train.validation);
      stages::runLidarSemanticMapTrain({list.begin(), list.end()}, {held.begin(), held.end()},
                                       train.out, params);
      return train.out;
    }
    if (drive.empty() || out.empty())
      throw ConfigError("a drive folder and -o/--out are required (or the train subcommand)");
    stages::runLidarSemanticMap(drive, out, params);
    return out;
  });
}
