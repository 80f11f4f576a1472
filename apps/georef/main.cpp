// georef: GPS + odometry pose graph per LSM (§4.1, eq. 4-6) -> LSMs in ENU of one shared origin.
#include "about.hpp"
#include "mapfuse/cli/app.hpp"
#include "mapfuse/stages/georef.hpp"

int main(int argc, char** argv) {
  using namespace mapfuse;
  return cli::lsmFolderMain<stages::GeorefParams>(argc, argv, "georef", apps::about::kGeoref,
                                                  stages::runGeoref);
}
