// File names that one input file gives for another (frames.json's calibration, frames.csv's
// masks, tiles.json's LSMs): they must name a file below the naming file's folder, and a name
// the file system cannot hold is bad input, not a crash (fuzz_drive_frames found
// std::filesystem throwing "File name too long" out of exists()).
#pragma once

#include <filesystem>
#include <string>
#include <system_error>

#include "mapfuse/core/error.hpp"

namespace mapfuse::io {

/// Longest part of a relative name (POSIX NAME_MAX on Linux file systems) and longest name.
inline constexpr std::size_t kMaxNamePart = 255;
inline constexpr std::size_t kMaxRelativeName = 1024;

/// Why `name` is not a relative path below its folder, or "" when it is: no root, no "." or
/// ".." part, no empty part, no control characters or backslashes, each part at most
/// kMaxNamePart bytes and the whole at most kMaxRelativeName.
inline std::string relativeNameProblem(const std::string& name) {
  if (name.empty()) return "is empty";
  if (name.size() > kMaxRelativeName)
    return "is " + std::to_string(name.size()) + " bytes long (at most " +
           std::to_string(kMaxRelativeName) + ")";
  if (name.front() == '/' || name.back() == '/' || name.find("//") != std::string::npos)
    return "'" + name + "' is not a path below the folder";
  for (unsigned char c : name)
    if (c < 0x20 || c == 0x7f || c == '\\') return "holds a control character or backslash";
  for (const auto& part : std::filesystem::path(name)) {
    if (part.empty() || part == "." || part == "..")
      return "'" + name + "' is not a path below the folder";
    if (part.native().size() > kMaxNamePart)
      return "has a part of " + std::to_string(part.native().size()) + " bytes (at most " +
             std::to_string(kMaxNamePart) + ")";
  }
  return {};
}

/// Whether `path` exists; an error other than "no such file" (a name too long, a permission
/// denied on a parent) is an IoError naming the path instead of std::filesystem's exception.
inline bool fileExists(const std::filesystem::path& path) {
  std::error_code ec;
  const auto st = std::filesystem::status(path, ec);
  if (ec && ec != std::errc::no_such_file_or_directory && ec != std::errc::not_a_directory)
    throw IoError(path.string(), ec.message());
  return std::filesystem::exists(st);
}

}  // namespace mapfuse::io
