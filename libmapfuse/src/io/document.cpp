#include "mapfuse/io/document.hpp"

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/atomic_file.hpp"

namespace mapfuse::io {

Encoding encodingOf(const std::filesystem::path& path) {
  const std::string ext = path.extension().string();
  if (ext == ".json" || ext == ".geojson") return Encoding::kJson;
  if (ext == ".cbor") return Encoding::kCbor;
  throw IoError(path.string(), "unknown extension '" + ext + "' (expected .json or .cbor)");
}

nlohmann::json readDocument(const std::filesystem::path& path) {
  const Encoding enc = encodingOf(path);
  const std::string bytes = readBytes(path);
  if (bytes.empty()) throw ParseError(path.string(), "", "file is empty");
  try {
    if (enc == Encoding::kCbor) return nlohmann::json::from_cbor(bytes.begin(), bytes.end());
    return nlohmann::json::parse(bytes);
  } catch (const nlohmann::json::exception& e) {
    throw ParseError(
        path.string(), "",
        std::string(enc == Encoding::kCbor ? "invalid CBOR: " : "invalid JSON: ") + e.what());
  }
}

void writeDocument(const std::filesystem::path& path, const nlohmann::json& doc, int indent) {
  const Encoding enc = encodingOf(path);
  if (enc == Encoding::kCbor) {
    const std::vector<uint8_t> bytes = nlohmann::json::to_cbor(doc);
    writeBytesAtomic(path, std::string(bytes.begin(), bytes.end()));
  } else {
    writeBytesAtomic(path, doc.dump(indent) + "\n");
  }
}

}  // namespace mapfuse::io
