// align: SGICP + PCM + multi-trajectory pose graph + GBA (§4.2, eq. 7-14) over georeferenced LSMs.
#include <iostream>

#include "mapfuse/cli/app.hpp"
#include "mapfuse/stages/align.hpp"

static const char* const kAbout =
    "Align georeferenced LSMs (one shared ENU origin): registrations between overlapping\n"
    "submaps of different traversals (--method icp | sicp | sgicp | gba_sgicp), PCM, a\n"
    "multi-trajectory pose graph, then GBA. Outputs below --out: one LSM per input (same file\n"
    "name), align.config.json, align.summary.json.\n"
    "Exit codes: 0 ok, 2 usage/config, 3 bad input, 4 I/O.";

int main(int argc, char** argv) {
  using namespace mapfuse;
  cli::StageTool<stages::AlignParams> tool("align", kAbout);
  std::vector<std::string> inputs;
  std::string out;
  tool.app()
      .add_option("lsms", inputs, "Input LSMs (.json/.cbor), @list.txt, or - for a list on stdin")
      ->required();
  tool.app().add_option("-o,--out", out, "Output folder (LSMs keep their file names)")->required();
  return tool.run(argc, argv, [&](const stages::AlignParams& params) {
    stages::runAlign(cli::expandInputList(inputs), out, params);
    std::cout << out << '\n';
  });
}
