/// @file aggregate: georeferenced or aligned LSMs -> vector map (§4.3, Song et al. 2023;
/// docs/aggregate.md). Prints the map size figures as JSON on stdout.
#include <iostream>

#include "mapfuse/cli/app.hpp"
#include "mapfuse/stages/aggregate.hpp"

int main(int argc, char** argv) {
  using namespace mapfuse;
  stages::AggregateParams params;
  cli::CommonOptions common;
  std::vector<std::string> inputs;
  std::string out_dir;
  CLI::App app{
      "Fuse LSMs in ENU (georef or align output, one shared origin) into a light vector HD map:\n"
      "two-stage DBSCAN lane instantiation, Bezier vectorization, discrete element merging.\n"
      "Outputs below --out: map.cbor (compact), map.json, map.geojson (WGS84), map.osm\n"
      "(Lanelet2-style), map.png, aggregate.config.json, aggregate.summary.json.\n"
      "Exit codes: 0 ok, 2 usage/config, 3 bad input (malformed LSM, frame odom, origin\n"
      "mismatch), 4 I/O.",
      "aggregate"};
  app.add_option("inputs", inputs, "LSM files (.json/.cbor); @list.txt or - (stdin) for lists")
      ->required();
  app.add_option("-o,--out", out_dir, "output folder")->required();
  cli::addCommonOptions(app, common);
  try {
    cli::preloadConfig(argc, argv, params);  // file values become the defaults
  } catch (const Error& e) {
    std::cerr << "aggregate: error: " << e.what() << "\n";
    return static_cast<int>(e.exitCode());
  }
  cli::addParamOptions(app, params);
  return cli::runStage(app, argc, argv, params, [&] {
    cli::applyCommonOptions(common);
    const auto summary = stages::runAggregate(cli::expandInputList(inputs), out_dir, params);
    std::cout << summary["size"].dump() << "\n";
  });
}
