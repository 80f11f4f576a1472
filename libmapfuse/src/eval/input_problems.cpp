#include "mapfuse/eval/input_problems.hpp"

#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"

namespace mapfuse::eval {

void warnOrRefuse(const std::vector<std::string>& problems, bool strict, const std::string& what,
                  std::vector<std::string>& noted) {
  for (const auto& p : problems) {
    if (strict) throw InputError(p + " (refused: --strict)");
    MAPFUSE_WARN(what << ": " << p);
    noted.push_back(p);
  }
}

}  // namespace mapfuse::eval
