#pragma once
/// @file JSON and CBOR documents sharing one schema, the encoding chosen by the file extension
/// (".json" text, ".cbor" nlohmann binary CBOR).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace mapfuse::io {

enum class Encoding { kJson, kCbor };

/// @brief Encoding of a path by extension. @throws IoError for any other extension.
Encoding encodingOf(const std::filesystem::path& path);

/// @brief Reads and parses a JSON or CBOR file.
/// @throws IoError (cannot read) or ParseError (syntax, truncation, nesting deeper than
/// bounds::kMaxNesting; names the byte offset).
nlohmann::json readDocument(const std::filesystem::path& path);

/// @brief Parses a JSON or CBOR document held in memory; `file` names the source in errors.
/// @throws ParseError as readDocument.
nlohmann::json parseDocument(const std::string& bytes, Encoding encoding, const std::string& file);

/// @brief Atomically writes a document; JSON is indented for reading (`indent` < 0: compact).
void writeDocument(const std::filesystem::path& path, const nlohmann::json& doc, int indent = 1);

}  // namespace mapfuse::io
