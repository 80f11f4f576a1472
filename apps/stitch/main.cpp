// stitch: merge per-tile vector maps into one map without duplicates or gaps at tile borders.
#include "mapfuse/cli/app.hpp"
#include "mapfuse/stages/stitch.hpp"

int main(int argc, char** argv) {
  using namespace mapfuse;
  CLI::App app("Merge per-tile vector maps (paths containing tile_<ix>_<iy>) into one map.",
               "stitch");
  tiling::StitchParams params;
  cli::CommonOptions common;
  std::vector<std::string> maps;
  std::string tiles_json, out;
  app.add_option("maps", maps, "Tile vector maps, @list.txt, or - for a list on stdin")->required();
  app.add_option("--tiles", tiles_json, "tiles.json written by `tile`")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("-o,--out", out, "Stitched map (.cbor or .json); a .geojson is written beside it")
      ->required();
  cli::addCommonOptions(app, common);
  cli::addParamOptions(app, params);
  return cli::runStage(app, argc, argv, params, [&] {
    cli::applyCommonOptions(common);
    const auto map = stages::runStitch(tiles_json, cli::expandInputList(maps), out, params);
    std::cout << out << '\n';
  });
}
