// lsm-build: one raw drive -> one local semantic map (LSM) (Song et al. 2023 §3).

#include "about.hpp"
#include "mapfuse/cli/app.hpp"
#include "mapfuse/stages/lsm_build.hpp"

int main(int argc, char** argv) {
  using namespace mapfuse;
  cli::StageTool<stages::LsmBuildParams> tool("lsm-build", apps::about::kLsmBuild);
  std::string drive, poses, drive_id;
  CLI::App& app = tool.app();
  app.add_option("drive", drive, "Drive folder: frames.json layout or a KITTI raw *_sync folder")
      ->required();
  const auto& out = tool.out("Output folder (<drive_id>.lsm.json, summary, PNG)");
  app.add_option("--poses", poses, "KITTI odometry poses file (egomotion = poses)");
  app.add_option("--drive-id", drive_id, "Drive id written into the LSM (default: from input)");
  return tool.run(argc, argv, [&](const stages::LsmBuildParams& params) {
    return stages::runLsmBuild({drive, out, poses, drive_id}, params).lsm_file.string();
  });
}
