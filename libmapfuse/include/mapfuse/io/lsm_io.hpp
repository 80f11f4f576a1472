#pragma once
/// @file LSM files (docs/formats.md "LSM"): format "mapfuse.lsm", version 1, JSON or CBOR by
/// extension.
#include <filesystem>
#include <string>
#include <vector>

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

/// @brief Reads the input LSMs of one run. The same file given twice (by path or by identity,
/// e.g. through a link) or one drive (drive_id) under two file names would count its data twice:
/// both are refused with a ConfigError (exit 2) naming the two inputs.
/// @param covariances false: each element's per-point covariances are dropped once its file is
/// read and checked (aggregate never uses them; they are three quarters of a decoded LSM).
std::vector<Lsm> readLsmInputs(const std::vector<std::string>& files, bool covariances = true);
/// @brief readLsmInputs' first rule alone, for stages that read their inputs one at a time:
/// @throws ConfigError when one file is given twice (by path or identity), naming both.
void refuseSameFile(const std::vector<std::string>& files);
/// @brief readLsmInputs' second rule: `drive_ids[i]` is the drive of `files[i]`.
/// @throws ConfigError when two files hold one drive, naming both.
void refuseSameDrive(const std::vector<std::string>& files,
                     const std::vector<std::string>& drive_ids);
/// @brief Atomic write (temp file + rename).
void writeLsm(const std::filesystem::path& path, const Lsm& lsm);
/// @brief Writes each input LSM again, whole, into `out_dir` under its file name, with the
/// keyframes of `updated[i]` (moved out; its elements are freed): for a run that held the
/// inputs without covariances. Files are done side by side; the first file's error is thrown.
void writeWithKeyframes(const std::vector<std::string>& inputs, std::vector<Lsm>& updated,
                        const std::filesystem::path& out_dir);

}  // namespace mapfuse::io
