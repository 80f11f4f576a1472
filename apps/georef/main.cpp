// georef: GPS + odometry pose graph per LSM (§4.1, eq. 4-6) -> LSMs in ENU of one shared origin.
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
  return cli::lsmFolderMain<stages::GeorefParams>(argc, argv, "georef", kAbout, stages::runGeoref);
}
