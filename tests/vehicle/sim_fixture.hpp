#pragma once
// A small simulated drive (simulate --level frames) shared by the lsm-build tests of one
// process; generated once into a temporary folder.
#include <cstdlib>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>

#include "support/test_support.hpp"

namespace mapfuse::test {

/// @brief Folder of one simulated drive (frames layout). `flat` disables the body pitch/roll
/// oscillation so a constant calibration error can be isolated; `straight` makes the world's
/// roads straight (--world-curve-amplitude 0): the vanishing-point calibration uses only
/// straight stretches (vehicle/vp_gate.hpp), and the default world's roads bulge everywhere.
inline std::filesystem::path simulatedDrive(bool flat, bool masks, bool straight = false) {
  namespace fs = std::filesystem;
  const fs::path sim = appPath("simulate");
  // Cache across the test processes of one ctest run, keyed by the simulator build time, so
  // each TEST_CASE process does not regenerate the drive.
  const auto stamp = fs::last_write_time(sim).time_since_epoch().count();
  const std::string name = std::string("sim_") + (flat ? "flat" : "osc") + (masks ? "_m" : "") +
                           (straight ? "_straight" : "") + "_" + std::to_string(stamp);
  const fs::path cache = fs::temp_directory_path() / "mapfuse-vehicle-test-cache" / name;
  if (!fs::exists(cache / "done")) {
    const fs::path tmp = tempDir(name);
    std::string cmd = sim.string() + " -o " + tmp.string() +
                      " --level frames --traversals 1 --route-length 250 --seed 11 --quiet" +
                      (masks ? "" : " --frames-masks 0") +
                      (flat ? " --pitch-amplitude 0 --roll-amplitude 0" : "") +
                      (straight ? " --world-curve-amplitude 0" : "") + " > /dev/null";
    if (runCommand(cmd) != 0) throw std::runtime_error("simulate failed: " + cmd);
    writeText(tmp / "done", "");
    fs::create_directories(cache.parent_path());
    std::error_code ec;
    fs::rename(tmp, cache, ec);  // another process may have won the race: fine
  }
  for (const auto& e : fs::directory_iterator(cache / "frames")) return e.path();
  throw std::runtime_error("simulate wrote no drive");
}

}  // namespace mapfuse::test
