#include "mapfuse/cli/params.hpp"

#include "mapfuse/io/document.hpp"

namespace mapfuse {

nlohmann::json readConfigFile(const std::string& file) {
  try {
    return io::readDocument(file);
  } catch (const ParseError& e) {
    // An empty, truncated or malformed configuration is a configuration error (exit 2).
    throw ConfigError(e.what());
  }
}

}  // namespace mapfuse
