/// @file aggregate: georeferenced or aligned LSMs -> vector map (§4.3, Song et al. 2023;
/// docs/aggregate.md). Prints the map size figures as JSON on stdout.

#include "mapfuse/cli/app.hpp"
#include "mapfuse/stages/aggregate.hpp"

static const char* const kAbout =
    "Fuse LSMs in ENU (georef or align output, one shared origin) into a light vector HD map:\n"
    "two-stage DBSCAN lane instantiation, Bezier vectorization, discrete element merging\n"
    "(--method grid_vote: the Qin et al. 2021 grid-vote baseline for the ground classes).\n"
    "Outputs below --out: map.cbor (compact), map.json, map.geojson (WGS84), map.osm\n"
    "(Lanelet2-style), map.png, aggregate.config.json, aggregate.summary.json.\n"
    "Exit codes: 0 ok, 2 usage/config, 3 bad input (malformed LSM, frame odom, origin\n"
    "mismatch), 4 I/O.";

int main(int argc, char** argv) {
  using namespace mapfuse;
  cli::StageTool<stages::AggregateParams> tool("aggregate", kAbout);
  const auto& inputs = tool.inputs("inputs", cli::kLsmListHelp);
  const auto& out = tool.out("output folder");
  return tool.run(argc, argv, [&](const stages::AggregateParams& params) {
    return stages::toJson(stages::runAggregate(inputs, out, params))["size"].dump();
  });
}
