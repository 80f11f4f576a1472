#pragma once
/// @file The version every tool prints for --version: the CMake project version and, when the
/// tree was a git checkout at configure time, `git describe --always --dirty` (one place:
/// CMakeLists.txt passes both to cli/version.cpp).
#include <string>

namespace mapfuse::cli {

/// @brief e.g. "mapfuse 0.1.0 (24703c8-dirty)".
std::string versionText();

}  // namespace mapfuse::cli
