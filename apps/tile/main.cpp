// tile: cut georeferenced LSMs into per-tile LSM sets with overlap margins, so that align and
// aggregate can run per tile (locally with make -j, or on a cluster through Snakemake).
#include <iostream>

#include "about.hpp"
#include "mapfuse/cli/app.hpp"
#include "mapfuse/stages/tile.hpp"

int main(int argc, char** argv) {
  using namespace mapfuse;
  return cli::lsmListMain<stages::TileParams>(
      argc, argv, "tile", apps::about::kTile, "lsms",
      "Output folder (tiles.json + one folder per tile)",
      [](const std::vector<std::string>& inputs, const std::string& out,
         const stages::TileParams& params) {
        const auto manifest = stages::runTile(inputs, out, params);
        for (const auto& t : manifest["tiles"]) std::cout << t["name"].get<std::string>() << '\n';
      });
}
