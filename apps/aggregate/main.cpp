/// @file aggregate: georeferenced or aligned LSMs -> vector map (§4.3, Song et al. 2023;
/// docs/aggregate.md). Prints the map size figures as JSON on stdout.

#include "about.hpp"
#include "mapfuse/cli/app.hpp"
#include "mapfuse/stages/aggregate.hpp"

int main(int argc, char** argv) {
  using namespace mapfuse;
  return cli::lsmListMain<stages::AggregateParams>(
      argc, argv, "aggregate", apps::about::kAggregate, "inputs", "output folder",
      [](const std::vector<std::string>& inputs, const std::string& out,
         const stages::AggregateParams& params) {
        return stages::toJson(stages::runAggregate(inputs, out, params))["size"].dump();
      });
}
