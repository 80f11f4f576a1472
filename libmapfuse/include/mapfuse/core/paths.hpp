#pragma once
/// @file Where mapfuse finds the shared data and models folder.
#include <filesystem>

namespace mapfuse {

/// @brief Folder holding data/ and models/: env MAPFUSE_SHARED, else the build-time default
/// (the checkout's ../shared).
std::filesystem::path sharedRoot();

}  // namespace mapfuse
