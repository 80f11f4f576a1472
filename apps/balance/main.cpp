// balance: place the independently aligned tiles of a tiled run consistently before aggregation
// (per-tile registration groups and per-drive georef errors solved together).

#include "mapfuse/cli/app.hpp"
#include "mapfuse/stages/balance.hpp"

static const char* const kAbout =
    "Place the tiles of a tiled run consistently: each tile's align leaves every group of\n"
    "drive pieces it registered together at the mean GPS error of those pieces; balance\n"
    "carries every drive's GPS error across the tiles it runs through and moves each group to\n"
    "where one untiled run would put it. Reads tiles.json and, per tile, align's output in\n"
    "<tile>/align/; writes the moved LSMs to <out>/<tile>/ (same file names) for aggregate,\n"
    "plus balance.config.json and balance.summary.json.\n"
    "Exit codes: 0 ok, 2 usage/config, 3 bad input (missing align output), 4 I/O.";

int main(int argc, char** argv) {
  using namespace mapfuse;
  cli::StageTool<stages::BalanceParams> tool("balance", kAbout);
  const auto& tiles_json = tool.existingFile("--tiles", "tiles.json written by `tile`");
  const auto& out = tool.out("Output folder (one folder per tile)");
  return tool.run(argc, argv, [&](const stages::BalanceParams& params) {
    stages::runBalance(tiles_json, out, params);
    return out;
  });
}
