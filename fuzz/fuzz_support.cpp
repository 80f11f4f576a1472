#include "fuzz_support.hpp"

#include <unistd.h>

#include <fstream>

namespace mapfuse::fuzz {

void fail(const std::string& what, const char* file, int line) {
  std::fprintf(stderr, "mapfuse fuzz finding: %s (%s:%d)\n", what.c_str(), file, line);
  std::abort();
}

std::vector<std::string> splitParts(const std::string& bytes, std::size_t n, bool binary) {
  static const std::string kSeparator = "\n====\n";
  std::vector<std::string> parts;
  std::size_t pos = 0;
  while (parts.size() + 1 < n) {
    const std::size_t at = bytes.find(kSeparator, pos);
    if (at == std::string::npos) break;
    parts.push_back(bytes.substr(pos, at - pos + (binary ? 0 : 1)));  // text: its last newline
    pos = at + kSeparator.size();
  }
  parts.push_back(bytes.substr(pos));
  return parts;
}

const std::filesystem::path& scratchDir() {
  static const std::filesystem::path dir = [] {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/mapfuse-fuzz-XXXXXX";
    if (!::mkdtemp(pattern.data())) fail("cannot create a scratch folder", __FILE__, __LINE__);
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(scratchDir(), ec);
    });
    return std::filesystem::path(pattern);
  }();
  return dir;
}

void writeFile(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) fail("cannot write " + path.string(), __FILE__, __LINE__);
}

}  // namespace mapfuse::fuzz
