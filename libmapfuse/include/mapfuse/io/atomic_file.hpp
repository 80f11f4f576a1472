#pragma once
/// @file Atomic file output: write to "<path>.tmp-<pid>" in the same folder, flush, then
/// rename over the target, so a failed or interrupted run never leaves a half-written file
/// and never destroys the previous one.
#include <filesystem>
#include <functional>
#include <ostream>
#include <string>

namespace mapfuse::io {

/// @brief Calls `write` with a stream to a temporary file, then renames it onto `path` (or, while
/// an OutputTransaction is open, leaves the rename to its commit).
/// Parent folders are created. If `write` throws, the temporary file is removed, the target
/// is untouched and the exception propagates.
/// @throws IoError when the file cannot be created, written or renamed.
void writeFileAtomic(const std::filesystem::path& path,
                     const std::function<void(std::ostream&)>& write);

/// @brief Atomic write of a byte string.
void writeBytesAtomic(const std::filesystem::path& path, const std::string& bytes);

/// @brief Reads a whole file. @throws IoError when it cannot be opened or read.
std::string readBytes(const std::filesystem::path& path);

}  // namespace mapfuse::io
