// balance: place the independently aligned tiles of a tiled run consistently before aggregation
// (per-tile registration groups and per-drive georef errors solved together).

#include "about.hpp"
#include "mapfuse/cli/app.hpp"
#include "mapfuse/stages/balance.hpp"

int main(int argc, char** argv) {
  using namespace mapfuse;
  cli::StageTool<stages::BalanceParams> tool("balance", apps::about::kBalance);
  const auto& tiles_json = tool.existingFile("--tiles", "tiles.json written by `tile`");
  const auto& out = tool.out("Output folder (one folder per tile)");
  return tool.run(argc, argv, [&](const stages::BalanceParams& params) {
    stages::runBalance(tiles_json, out, params);
    return out;
  });
}
