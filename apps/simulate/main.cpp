// simulate: crowdsourced drives with ground truth (docs/simulate.md); prints the summary JSON.

#include "about.hpp"
#include "mapfuse/cli/app.hpp"
#include "mapfuse/stages/simulate.hpp"

int main(int argc, char** argv) {
  using namespace mapfuse;
  cli::StageTool<stages::SimulateParams> tool("simulate", apps::about::kSimulate);
  const auto& out = tool.out("output folder");
  return tool.run(argc, argv, [&](const stages::SimulateParams& params) {
    const auto run = stages::runSimulate(params, out);
    nlohmann::json summary = stages::toJson(run);
    summary["seconds"] = run.seconds;
    return summary.dump(2);
  });
}
