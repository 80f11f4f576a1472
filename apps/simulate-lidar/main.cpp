// simulate-lidar: a seeded synthetic KITTI raw drive (Velodyne, OXTS, image_02, calibration)
// with LiDAR + camera ground truth: true SemanticKITTI labels per point, true label images and
// network-like class probabilities (semantics_02/*.prob). See docs/lidar-ground-truth.md.

#include "about.hpp"
#include "mapfuse/cli/app.hpp"
#include "mapfuse/stages/simulate_lidar.hpp"

int main(int argc, char** argv) {
  using namespace mapfuse;
  cli::StageTool<stages::SimulateLidarParams> tool("simulate-lidar", apps::about::kSimulateLidar);
  const auto& out = tool.out("Output root: <out>/<date>/<date>_drive_<drive>_sync");
  return tool.run(argc, argv, [&](const stages::SimulateLidarParams& params) {
    return stages::runSimulateLidar(out, params).drive_dir.string();
  });
}
