// align: SGICP + PCM + multi-trajectory pose graph + GBA (§4.2, eq. 7-14) over georeferenced LSMs.
#include <iostream>

#include "mapfuse/cli/app.hpp"
#include "mapfuse/stages/align.hpp"

int main(int argc, char** argv) {
  using namespace mapfuse;
  CLI::App app{
      "Align georeferenced LSMs (one shared ENU origin): registrations between overlapping\n"
      "submaps of different traversals (--method icp | sicp | sgicp | gba_sgicp), PCM, a\n"
      "multi-trajectory pose graph, then GBA. Outputs below --out: one LSM per input (same file\n"
      "name), align.config.json, align.summary.json.\n"
      "Exit codes: 0 ok, 2 usage/config, 3 bad input, 4 I/O.",
      "align"};
  stages::AlignParams params;
  cli::CommonOptions common;
  std::vector<std::string> inputs;
  std::string out;
  app.add_option("lsms", inputs, "Input LSMs (.json/.cbor), @list.txt, or - for a list on stdin")
      ->required();
  app.add_option("-o,--out", out, "Output folder (LSMs keep their file names)")->required();
  cli::addCommonOptions(app, common);
  try {
    cli::preloadConfig(argc, argv, params);  // file values become the defaults
  } catch (const Error& e) {
    std::cerr << "align: error: " << e.what() << "\n";
    return static_cast<int>(e.exitCode());
  }
  cli::addParamOptions(app, params);
  return cli::runStage(app, argc, argv, params, [&] {
    cli::applyCommonOptions(common);
    const auto summary = stages::runAlign(cli::expandInputList(inputs), out, params);
    std::cout << out << '\n';
  });
}
