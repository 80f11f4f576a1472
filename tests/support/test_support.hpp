#pragma once
/// @file Helpers shared by the Catch2 tests: shared-data lookup, temp folders, running apps.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace mapfuse::test {

/// @brief A vector of random draws of `dist` in a fixed order, whatever the compiler: the last
/// component first (what gcc gave `Vector3d(d(rng), d(rng), d(rng))`, whose unsequenced arguments
/// clang evaluates the other way), so that a fixture is the same world under gcc and clang and
/// keeps the values the tests were written with.
template <class Vec, class Dist, class Rng>
Vec drawVector(Dist& dist, Rng& rng) {
  Vec v;
  for (int i = int(v.size()) - 1; i >= 0; --i) v[i] = dist(rng);
  return v;
}

/// Exit code ctest maps to "skipped" (SKIP_RETURN_CODE in tests/CMakeLists.txt).
constexpr int kSkipExitCode = 77;

/// @brief Path of a file under the shared data folder (env MAPFUSE_SHARED, else ../shared).
/// Prints a visible SKIP line and exits with kSkipExitCode when it is absent.
/// @param relative path below the shared folder, e.g. "data/kitti_raw/2011_09_26".
std::filesystem::path requireShared(const std::string& relative);

/// @brief A fresh, empty temporary folder unique to this test process.
std::filesystem::path tempDir(const std::string& name);

/// @brief Path of a built executable (env MAPFUSE_BIN_DIR, else the build's bin folder).
std::filesystem::path appPath(const std::string& tool);

/// @brief Runs a shell command; returns its exit status (0-255).
int runCommand(const std::string& command);

/// @brief Runs `simulate --map <dir>/<map> --traversals 1 --route-length 60 --level truth
/// <extra> -o <dir>/<name>` (a map import in one short truth-only run), stdout dropped, stderr
/// in `<dir>/<name>.err`. @return its exit status.
int simulateTruthOn(const std::filesystem::path& dir, const std::string& map,
                    const std::string& extra, const std::string& name);

/// @brief Writes text to a file (test fixtures).
void writeText(const std::filesystem::path& path, const std::string& text);

/// @brief Reads a whole file as bytes.
std::string readText(const std::filesystem::path& path);

/// @brief `<dir>/<stage>.summary.json`, parsed.
nlohmann::json readSummary(const std::filesystem::path& dir, const std::string& stage);

}  // namespace mapfuse::test
