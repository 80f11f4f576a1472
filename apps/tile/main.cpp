// tile: cut georeferenced LSMs into per-tile LSM sets with overlap margins, so that align and
// aggregate can run per tile (locally with make -j, or on a cluster through Snakemake).
#include "mapfuse/cli/app.hpp"
#include "mapfuse/stages/tile.hpp"

int main(int argc, char** argv) {
  using namespace mapfuse;
  CLI::App app("Cut georeferenced LSMs (frame enu) into per-tile LSM sets.", "tile");
  stages::TileParams params;
  cli::CommonOptions common;
  std::vector<std::string> inputs;
  std::string out;
  app.add_option("lsms", inputs, "LSM files (.json/.cbor), @list.txt, or - for a list on stdin")
      ->required();
  app.add_option("-o,--out", out, "Output folder (tiles.json + one folder per tile)")->required();
  cli::addCommonOptions(app, common);
  cli::addParamOptions(app, params);
  return cli::runStage(app, argc, argv, params, [&] {
    cli::applyCommonOptions(common);
    const auto manifest = stages::runTile(cli::expandInputList(inputs), out, params);
    for (const auto& t : manifest["tiles"]) std::cout << t["name"].get<std::string>() << '\n';
  });
}
