#pragma once
/// @file JSON and CBOR documents sharing one schema, the encoding chosen by the file extension
/// (".json" text, ".cbor" nlohmann binary CBOR).
#include <filesystem>
#include <nlohmann/json.hpp>

namespace mapfuse::io {

enum class Encoding { kJson, kCbor };

/// @brief Encoding of a path by extension. @throws IoError for any other extension.
Encoding encodingOf(const std::filesystem::path& path);

/// @brief Reads and parses a JSON or CBOR file.
/// @throws IoError (cannot read) or ParseError (syntax, truncation; names the byte offset).
nlohmann::json readDocument(const std::filesystem::path& path);

/// @brief Atomically writes a document; JSON is indented for reading (`indent` < 0: compact).
void writeDocument(const std::filesystem::path& path, const nlohmann::json& doc, int indent = 1);

}  // namespace mapfuse::io
