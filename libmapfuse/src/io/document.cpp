#include "mapfuse/io/document.hpp"

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/bounds.hpp"
#include "utf8.hpp"

namespace mapfuse::io {
namespace {

using Json = nlohmann::json;

// nlohmann's DOM builder behind a nesting limit. The CBOR reader recurses once per nested array
// or object (a 500 KB file of nested arrays overflowed the stack); refusing the level past
// bounds::kMaxNesting in start_array / start_object stops it before the recursion goes deeper.
class DepthLimitedSax {
 public:
  /// `check_text`: check strings and keys as UTF-8 (CBOR; JSON's lexer already refuses bad UTF-8).
  DepthLimitedSax(Json& root, bool check_text)
      : dom_(root, /*allow_exceptions=*/true), check_text_(check_text) {}

  bool null() { return dom_.null(); }
  bool boolean(bool v) { return dom_.boolean(v); }
  bool number_integer(Json::number_integer_t v) { return dom_.number_integer(v); }
  bool number_unsigned(Json::number_unsigned_t v) { return dom_.number_unsigned(v); }
  bool number_float(Json::number_float_t v, const std::string& s) {
    return dom_.number_float(v, s);
  }
  bool string(std::string& s) { return text(s, "a text string") && dom_.string(s); }
  bool binary(Json::binary_t& b) { return dom_.binary(b); }
  bool start_object(std::size_t n) { return enter() && dom_.start_object(n); }
  bool key(std::string& k) { return text(k, "a key") && dom_.key(k); }
  bool end_object() {
    --depth_;
    return dom_.end_object();
  }
  bool start_array(std::size_t n) { return enter() && dom_.start_array(n); }
  bool end_array() {
    --depth_;
    return dom_.end_array();
  }
  bool parse_error(std::size_t /*position*/, const std::string& /*token*/,
                   const nlohmann::detail::exception& e) {
    error_ = e.what();
    return false;
  }

  const std::string& error() const { return error_; }

 private:
  bool text(const std::string& s, const char* what) {
    if (!check_text_ || validUtf8(s)) return true;
    error_ = std::string(what) + " is not valid UTF-8";
    return false;
  }
  bool enter() {
    if (++depth_ <= bounds::kMaxNesting) return true;
    error_ = "nested deeper than " + std::to_string(bounds::kMaxNesting) + " arrays or objects";
    return false;
  }
  nlohmann::detail::json_sax_dom_parser<Json> dom_;
  bool check_text_;
  int depth_ = 0;
  std::string error_;
};

}  // namespace

Encoding encodingOf(const std::filesystem::path& path) {
  const std::string ext = path.extension().string();
  if (ext == ".json" || ext == ".geojson") return Encoding::kJson;
  if (ext == ".cbor") return Encoding::kCbor;
  throw IoError(path.string(), "unknown extension '" + ext + "' (expected .json or .cbor)");
}

Json parseDocument(const std::string& bytes, Encoding encoding, const std::string& file) {
  const char* what = encoding == Encoding::kCbor ? "invalid CBOR: " : "invalid JSON: ";
  if (bytes.empty()) throw ParseError(file, "", "file is empty");
  Json doc;
  DepthLimitedSax sax(doc, /*check_text=*/encoding == Encoding::kCbor);
  bool ok = false;
  try {
    ok = encoding == Encoding::kCbor
             ? Json::sax_parse(bytes.begin(), bytes.end(), &sax, Json::input_format_t::cbor)
             : Json::sax_parse(bytes.begin(), bytes.end(), &sax, Json::input_format_t::json);
  } catch (const Json::exception& e) {
    throw ParseError(file, "", what + std::string(e.what()));
  }
  if (!ok) throw ParseError(file, "", what + (sax.error().empty() ? "malformed" : sax.error()));
  return doc;
}

Json readDocument(const std::filesystem::path& path) {
  const Encoding enc = encodingOf(path);
  return parseDocument(readBytes(path), enc, path.string());
}

void writeDocument(const std::filesystem::path& path, const Json& doc, int indent) {
  const Encoding enc = encodingOf(path);
  if (enc == Encoding::kCbor) {
    const std::vector<uint8_t> bytes = Json::to_cbor(doc);
    writeBytesAtomic(path, std::string(bytes.begin(), bytes.end()));
  } else {
    writeBytesAtomic(path, doc.dump(indent) + "\n");
  }
}

}  // namespace mapfuse::io
