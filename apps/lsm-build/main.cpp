// lsm-build: one raw drive (simulate --level frames folder, or a KITTI raw drive with a poses
// file) -> one local semantic map (LSM) in the drive's odom frame (Song et al. 2023 §3).
#include "mapfuse/cli/app.hpp"
#include "mapfuse/stages/lsm_build.hpp"

int main(int argc, char** argv) {
  using namespace mapfuse;
  CLI::App app(
      "Build a local semantic map (LSM) from one drive: camera semantics + ego-motion "
      "(docs/lsm-build.md).",
      "lsm-build");
  stages::LsmBuildParams params;
  stages::LsmBuildInputs inputs;
  cli::CommonOptions common;
  std::string drive, out, poses;
  app.add_option("drive", drive, "Drive folder: frames.json layout or a KITTI raw *_sync folder")
      ->required();
  app.add_option("-o,--out", out, "Output folder (<drive_id>.lsm.json, summary, PNG)")->required();
  app.add_option("--poses", poses, "KITTI odometry poses file (egomotion = poses)");
  app.add_option("--drive-id", inputs.drive_id,
                 "Drive id written into the LSM (default: from input)");
  cli::addCommonOptions(app, common);
  cli::addParamOptions(app, params);
  cli::preloadConfig(argc, argv, params);
  return cli::runStage(app, argc, argv, params, [&] {
    cli::applyCommonOptions(common);
    inputs.drive = drive;
    inputs.out = out;
    inputs.poses = poses;
    const auto result = stages::runLsmBuild(inputs, params);
    std::cout << result.lsm_file.string() << '\n';
  });
}
