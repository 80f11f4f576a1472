#pragma once
/// @file LSM files (docs/formats.md "LSM"): format "mapfuse.lsm", version 1, JSON or CBOR by
/// extension.
#include <filesystem>

#include "mapfuse/core/lsm.hpp"
#include "mapfuse/io/json_view.hpp"

namespace mapfuse::io {

constexpr const char* kLsmFormat = "mapfuse.lsm";
constexpr int kLsmVersion = 1;

Json lsmToJson(const Lsm& lsm);
/// @brief Strict parse; `file` names the source in errors. @throws ParseError, InputError.
Lsm lsmFromJson(const Json& doc, const std::string& file);

/// @throws IoError, ParseError (file, field, problem), InputError (inconsistent content).
Lsm readLsm(const std::filesystem::path& path);
/// @brief Atomic write (temp file + rename).
void writeLsm(const std::filesystem::path& path, const Lsm& lsm);

}  // namespace mapfuse::io
