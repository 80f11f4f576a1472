#include "version.hpp"

#ifndef MAPFUSE_VERSION
#define MAPFUSE_VERSION "unknown"
#endif
#ifndef MAPFUSE_GIT_DESCRIBE
#define MAPFUSE_GIT_DESCRIBE ""
#endif

namespace mapfuse::cli {

std::string versionText() {
  std::string text = std::string("mapfuse ") + MAPFUSE_VERSION;
  const std::string git = MAPFUSE_GIT_DESCRIBE;
  if (!git.empty()) text += " (" + git + ")";
  return text;
}

}  // namespace mapfuse::cli
