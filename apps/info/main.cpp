// info: what mapfuse files hold (one JSON object per line on stdout), or the shared ENU origin
// of a batch (--origin), for scripts and Makefiles.
#include <iomanip>
#include <iostream>

#include "about.hpp"
#include "mapfuse/cli/app.hpp"
#include "mapfuse/stages/info.hpp"

int main(int argc, char** argv) {
  using namespace mapfuse;
  cli::StageTool<stages::InfoParams> tool("info", apps::about::kInfo);
  const auto& paths = tool.inputs("files", "mapfuse files, @list.txt, or - for a list on stdin");
  bool origin = false;
  tool.app().add_flag("--origin", origin,
                      "Print the shared ENU origin as lat,lon,alt: of the first file, an LSM (its "
                      "origin, else its first GPS fix) or a vector map (its origin)");
  return tool.run(argc, argv, [&](const stages::InfoParams&) {
    if (origin) {
      const geo::GeoOrigin o = stages::originOf(paths.at(0));
      std::cout << std::setprecision(12) << o.lat << ',' << o.lon << ',' << std::setprecision(8)
                << o.alt << '\n';
      return;
    }
    for (const auto& p : paths) std::cout << stages::toJson(stages::describeFile(p)).dump() << '\n';
  });
}
