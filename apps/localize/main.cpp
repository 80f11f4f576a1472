// localize: localisation of georeferenced drives on a vector map (Song et al. 2023 §5, Fig. 12).

#include "mapfuse/cli/app.hpp"
#include "mapfuse/stages/localize.hpp"

static const char* const kAbout =
    "Localise georeferenced drives (LSMs, frame enu) on a vector map: per keyframe, observed\n"
    "lane / stop line points point-to-line, poles / lights / planar centres point-to-point,\n"
    "Cauchy loss, the georeferenced (GPS) pose as a weak prior; then (solve full_drive) all\n"
    "keyframes of a drive in one problem chained by its relative motion. Frames level\n"
    "(--frames DIR): every camera frame of the raw drives in DIR, from lsm-build's per-frame\n"
    "ranging; the LSMs are then lsm-build's of these drives, georeferenced. Outputs below --out:\n"
    "<drive>.trajectory.json; with --truth-trajectories <drive>.errors.csv and .errors.png;\n"
    "localize.config.json, localize.summary.json (mean lateral / longitudinal / heading; with\n"
    "--truth-map also in the map's own frame).\n"
    "Exit codes: 0 ok, 2 usage/config, 3 bad input or map lost (> max_lost_share), 4 I/O.";

int main(int argc, char** argv) {
  using namespace mapfuse;
  cli::StageTool<stages::LocalizeParams> tool("localize", kAbout);
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
