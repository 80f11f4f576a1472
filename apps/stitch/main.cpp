// stitch: merge per-tile vector maps into one map without duplicates or gaps at tile borders.
#include <iostream>

#include "mapfuse/cli/app.hpp"
#include "mapfuse/stages/stitch.hpp"

int main(int argc, char** argv) {
  using namespace mapfuse;
  cli::StageTool<tiling::StitchParams> tool(
      "stitch", "Merge per-tile vector maps (paths containing tile_<ix>_<iy>) into one map.");
  std::vector<std::string> maps;
  std::string tiles_json, out;
  tool.app()
      .add_option("maps", maps, "Tile vector maps, @list.txt, or - for a list on stdin")
      ->required();
  tool.app()
      .add_option("--tiles", tiles_json, "tiles.json written by `tile`")
      ->required()
      ->check(CLI::ExistingFile);
  tool.app()
      .add_option("-o,--out", out, "Stitched map (.cbor or .json); a .geojson is written beside it")
      ->required();
  return tool.run(argc, argv, [&](const tiling::StitchParams& params) {
    stages::runStitch(tiles_json, cli::expandInputList(maps), out, params);
    std::cout << out << '\n';
  });
}
