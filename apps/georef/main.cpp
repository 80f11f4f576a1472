// georef: GPS + odometry pose graph per LSM (§4.1, eq. 4-6) -> LSMs in ENU of one shared origin.
#include <iostream>

#include "mapfuse/cli/app.hpp"
#include "mapfuse/stages/georef.hpp"

static const char* const kAbout =
    "Georeference LSMs: fuse keyframe odometry and GPS fixes in a Ceres pose graph (Cauchy\n"
    "loss, chi-square rejection of multipath fixes) and write each LSM in ENU of one shared\n"
    "origin (--origin, or the first GPS fix of the first LSM). Outputs below --out: one LSM per\n"
    "input (same file name), georef.config.json, georef.summary.json.\n"
    "Exit codes: 0 ok, 2 usage/config, 3 bad input, 4 I/O.";

int main(int argc, char** argv) {
  using namespace mapfuse;
  cli::StageTool<stages::GeorefParams> tool("georef", kAbout);
  std::vector<std::string> inputs;
  std::string out;
  tool.app()
      .add_option("lsms", inputs, "Input LSMs (.json/.cbor), @list.txt, or - for a list on stdin")
      ->required();
  tool.app().add_option("-o,--out", out, "Output folder (LSMs keep their file names)")->required();
  return tool.run(argc, argv, [&](const stages::GeorefParams& params) {
    stages::runGeoref(cli::expandInputList(inputs), out, params);
    std::cout << out << '\n';
  });
}
