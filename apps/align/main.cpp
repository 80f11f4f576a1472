// align: SGICP + PCM + multi-trajectory pose graph + GBA (§4.2, eq. 7-14) over georeferenced LSMs.
#include "mapfuse/cli/app.hpp"
#include "mapfuse/stages/align.hpp"

static const char* const kAbout =
    "Align georeferenced LSMs (one shared ENU origin): registrations between overlapping\n"
    "submaps of different traversals (--method icp | sicp | sgicp | gba_sgicp), PCM, a\n"
    "multi-trajectory pose graph, then GBA. Outputs below --out: one LSM per input (same file\n"
    "name), align.config.json, align.summary.json.\n"
    "Exit codes: 0 ok, 2 usage/config, 3 bad input, 4 I/O.";

int main(int argc, char** argv) {
  using namespace mapfuse;
  return cli::lsmFolderMain<stages::AlignParams>(argc, argv, "align", kAbout, stages::runAlign);
}
