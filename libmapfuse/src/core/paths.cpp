#include "mapfuse/core/paths.hpp"

#include <cstdlib>

namespace mapfuse {

std::filesystem::path sharedRoot() {
  if (const char* env = std::getenv("MAPFUSE_SHARED"); env && *env) return env;
  return MAPFUSE_DEFAULT_SHARED;
}

}  // namespace mapfuse
