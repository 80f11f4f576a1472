// localize: localisation of georeferenced drives on a vector map (Song et al. 2023 §5, Fig. 12).

#include "about.hpp"
#include "mapfuse/cli/app.hpp"
#include "mapfuse/stages/localize.hpp"

int main(int argc, char** argv) {
  using namespace mapfuse;
  cli::StageTool<stages::LocalizeParams> tool("localize", apps::about::kLocalize);
  stages::LocalizeInputs in;
  auto& app = tool.app();
  const auto& lsms = tool.inputs("lsms", "Drives: LSMs (.json/.cbor), @list.txt, or - (stdin)");
  app.add_option("--map", in.map, "Vector map (.json/.cbor): aggregate's or simulate's truth")
      ->required();
  app.add_option("--truth-trajectories", in.truth_trajectories,
                 "Folder of <drive>.trajectory.json (simulate truth/): score the errors");
  app.add_option("--truth-map", in.truth_map,
                 "Truth vector map: also score the errors in the map's frame (rigid map-to-truth)");
  app.add_option("--frames", in.frames_dir,
                 "Frames level: folder of raw drives (<drive_id>/frames.json) the LSMs were built "
                 "from");
  app.add_option("--lsm-build-config", in.lsm_build_config,
                 "Frames level: the lsm-build.config.json the LSMs were built with (default: "
                 "lsm-build's defaults)");
  const auto& out = tool.out("Output folder");
  return tool.run(argc, argv, [&](const stages::LocalizeParams& params) {
    in.lsms = lsms;
    stages::runLocalize(in, out, params);
    return out;
  });
}
