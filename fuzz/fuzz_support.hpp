#pragma once
/// @file What every fuzz target shares (fuzz/README.md). A target feeds libFuzzer's bytes to one
/// reader and checks three properties: (1) the reader either returns or throws one of the
/// project's errors with the documented exit code (3 for bad data; 2 for configuration files):
/// any other exception, a crash, a sanitizer report, a hang or an allocation past the limit is
/// a finding; (2) what it accepts respects the bounds of docs/formats.md "Value bounds";
/// (3) where the format has a writer, what it accepted and wrote is read back.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <initializer_list>
#include <string>
#include <vector>

#include "mapfuse/core/error.hpp"

namespace mapfuse::fuzz {

/// @brief The fuzzer's bytes as a string.
inline std::string bytesOf(const uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

/// @brief Aborts (a finding) with a message naming what failed.
[[noreturn]] void fail(const std::string& what, const char* file, int line);

/// @brief Runs `read`: true when it returns, false when it refuses the input with a mapfuse
/// error of one of the `allowed` exit codes. Any other mapfuse error aborts; any other exception
/// escapes to libFuzzer, which reports it as a crash.
template <class F>
bool accepts(F&& read, std::initializer_list<ExitCode> allowed = {ExitCode::kBadInput}) {
  try {
    read();
    return true;
  } catch (const Error& e) {
    for (ExitCode code : allowed)
      if (e.exitCode() == code) return false;
    fail("error with exit code " + std::to_string(int(e.exitCode())) + ": " + e.what(), __FILE__,
         __LINE__);
  }
}

/// @brief Splits an input into at most `n` parts at lines holding only "====" (multi-file
/// targets); missing parts are absent (nullopt-like: returned vector is shorter). A part keeps
/// the newline before its separator unless `binary` (Velodyne scans, labels, CBOR maps: the
/// newline is the separator's, not the file's).
std::vector<std::string> splitParts(const std::string& bytes, std::size_t n, bool binary = false);

/// @brief A scratch folder of this process (created once, under $TMPDIR or /tmp) for targets
/// whose reader takes a folder.
const std::filesystem::path& scratchDir();

/// @brief Writes `bytes` to `path` (plain, not atomic: the scratch folder is private).
void writeFile(const std::filesystem::path& path, const std::string& bytes);

}  // namespace mapfuse::fuzz

/// A property a target checks on accepted input: aborts with the condition when false.
#define MAPFUSE_FUZZ_CHECK(cond)                                                    \
  do {                                                                              \
    if (!(cond)) ::mapfuse::fuzz::fail("check failed: " #cond, __FILE__, __LINE__); \
  } while (0)
