// stitch: merge per-tile vector maps into one map without duplicates or gaps at tile borders.

#include "about.hpp"
#include "mapfuse/cli/app.hpp"
#include "mapfuse/stages/stitch.hpp"

int main(int argc, char** argv) {
  using namespace mapfuse;
  cli::StageTool<tiling::StitchParams> tool("stitch", apps::about::kStitch);
  const auto& maps = tool.inputs("maps", "Tile vector maps, @list.txt, or - for a list on stdin");
  const auto& tiles_json = tool.existingFile("--tiles", "tiles.json written by `tile`");
  const auto& out = tool.out("Stitched map (.cbor or .json); a .geojson is written beside it");
  return tool.run(argc, argv, [&](const tiling::StitchParams& params) {
    stages::runStitch(tiles_json, maps, out, params);
    return out;
  });
}
