// align: SGICP + PCM + multi-trajectory pose graph + GBA (§4.2, eq. 7-14) over georeferenced LSMs.
#include "about.hpp"
#include "mapfuse/cli/app.hpp"
#include "mapfuse/stages/align.hpp"

int main(int argc, char** argv) {
  using namespace mapfuse;
  return cli::lsmFolderMain<stages::AlignParams>(argc, argv, "align", apps::about::kAlign,
                                                 stages::runAlign);
}
