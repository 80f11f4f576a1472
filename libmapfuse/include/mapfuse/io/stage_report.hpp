#pragma once
/// @file What every stage writes beside its outputs: the resolved configuration
/// (<stage>.config.json) and the result summary (<stage>.summary.json), both atomically.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace mapfuse::io {

/// @brief Writes <dir>/<stage>.config.json with the parameters actually used.
void writeResolvedConfig(const std::filesystem::path& dir, const std::string& stage,
                         const nlohmann::json& params);

/// @brief Writes <dir>/<stage>.summary.json; adds "stage", "mapfuse_version" and "format".
void writeSummary(const std::filesystem::path& dir, const std::string& stage,
                  nlohmann::json summary);

}  // namespace mapfuse::io
