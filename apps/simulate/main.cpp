// simulate: crowdsourced drives over the procedural world or a Lanelet2 map, with ground truth
// (docs/simulate.md). Prints the summary JSON on stdout.
#include <iostream>

#include "mapfuse/cli/app.hpp"
#include "mapfuse/stages/simulate.hpp"

int main(int argc, char** argv) {
  using namespace mapfuse;
  stages::SimulateParams params;
  cli::CommonOptions common;
  std::string out_dir;
  CLI::App app{
      "Simulate crowdsourced drives (LSMs, raw frames) with ground truth.\n"
      "Outputs below --out: truth/vector_map.json(.geojson), truth/<drive>.trajectory.json,\n"
      "lsm/<drive>.lsm.cbor|json (--level lsm), frames/<drive>/ (--level frames),\n"
      "simulate.config.json, simulate.summary.json. Exit codes: 0 ok, 2 usage/config,\n"
      "3 bad input (malformed map), 4 I/O (missing map, unwritable output).",
      "simulate"};
  app.add_option("-o,--out", out_dir, "output folder")->required();
  cli::addCommonOptions(app, common);
  try {
    cli::preloadConfig(argc, argv, params);
  } catch (const Error& e) {
    std::cerr << "simulate: error: " << e.what() << "\n";
    return static_cast<int>(e.exitCode());
  }
  cli::addParamOptions(app, params);
  return cli::runStage(app, argc, argv, params, [&] {
    cli::applyCommonOptions(common);
    const auto result = stages::runSimulate(params, out_dir);
    std::cout << result.summary.dump(2) << "\n";
  });
}
