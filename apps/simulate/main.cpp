// simulate: crowdsourced drives with ground truth (docs/simulate.md); prints the summary JSON.

#include "mapfuse/cli/app.hpp"
#include "mapfuse/stages/simulate.hpp"

static const char* const kAbout =
    "Simulate crowdsourced drives (LSMs, raw frames) with ground truth.\n"
    "Outputs below --out: truth/vector_map.json(.geojson), truth/<drive>.trajectory.json,\n"
    "lsm/<drive>.lsm.cbor|json (--level lsm), frames/<drive>/ (--level frames),\n"
    "simulate.config.json, simulate.summary.json. Exit codes: 0 ok, 2 usage/config,\n"
    "3 bad input (malformed map), 4 I/O (missing map, unwritable output).";

int main(int argc, char** argv) {
  using namespace mapfuse;
  cli::StageTool<stages::SimulateParams> tool("simulate", kAbout);
  const auto& out = tool.out("output folder");
  return tool.run(argc, argv, [&](const stages::SimulateParams& params) {
    const auto run = stages::runSimulate(params, out);
    nlohmann::json summary = stages::toJson(run);
    summary["seconds"] = run.seconds;
    return summary.dump(2);
  });
}
