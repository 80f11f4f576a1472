// simulate-lidar: a seeded synthetic KITTI raw drive (Velodyne, OXTS, image_02, calibration)
// with LiDAR + camera ground truth: true SemanticKITTI labels per point, true label images and
// network-like class probabilities (semantics_02/*.prob). See docs/lidar-ground-truth.md.
#include <iostream>

#include "mapfuse/cli/app.hpp"
#include "mapfuse/stages/simulate_lidar.hpp"

int main(int argc, char** argv) {
  using namespace mapfuse;
  CLI::App app("Simulate a labelled KITTI raw drive (LiDAR + camera ground truth).",
               "simulate-lidar");
  stages::SimulateLidarParams params;
  cli::CommonOptions common;
  std::string out;
  app.add_option("-o,--out", out, "Output root: <out>/<date>/<date>_drive_<drive>_sync")
      ->required();
  cli::addCommonOptions(app, common);
  cli::addParamOptions(app, params);
  cli::preloadConfig(argc, argv, params);
  return cli::runStage(app, argc, argv, params, [&] {
    cli::applyCommonOptions(common);
    const auto summary = stages::runSimulateLidar(out, params);
    std::cout << summary["drive_dir"].get<std::string>() << '\n';
  });
}
