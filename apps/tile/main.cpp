// tile: cut georeferenced LSMs into per-tile LSM sets with overlap margins, so that align and
// aggregate can run per tile (locally with make -j, or on a cluster through Snakemake).
#include <iostream>

#include "mapfuse/cli/app.hpp"
#include "mapfuse/stages/tile.hpp"

int main(int argc, char** argv) {
  using namespace mapfuse;
  cli::StageTool<stages::TileParams> tool(
      "tile", "Cut georeferenced LSMs (frame enu) into per-tile LSM sets.");
  const auto& inputs = tool.inputs("lsms", cli::kLsmListHelp);
  const auto& out = tool.out("Output folder (tiles.json + one folder per tile)");
  return tool.run(argc, argv, [&](const stages::TileParams& params) {
    const auto manifest = stages::runTile(inputs, out, params);
    for (const auto& t : manifest["tiles"]) std::cout << t["name"].get<std::string>() << '\n';
  });
}
