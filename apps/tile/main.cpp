// tile: cut georeferenced LSMs into per-tile LSM sets with overlap margins, so that align and
// aggregate can run per tile (locally with make -j, or on a cluster through Snakemake).
#include <iostream>

#include "mapfuse/cli/app.hpp"
#include "mapfuse/stages/tile.hpp"

int main(int argc, char** argv) {
  using namespace mapfuse;
  cli::StageTool<stages::TileParams> tool(
      "tile", "Cut georeferenced LSMs (frame enu) into per-tile LSM sets.");
  std::vector<std::string> inputs;
  std::string out;
  tool.app()
      .add_option("lsms", inputs, "LSM files (.json/.cbor), @list.txt, or - for a list on stdin")
      ->required();
  tool.app()
      .add_option("-o,--out", out, "Output folder (tiles.json + one folder per tile)")
      ->required();
  return tool.run(argc, argv, [&](const stages::TileParams& params) {
    const auto manifest = stages::runTile(cli::expandInputList(inputs), out, params);
    for (const auto& t : manifest["tiles"]) std::cout << t["name"].get<std::string>() << '\n';
  });
}
