#pragma once
/// @file Inputs an evaluation cannot score (eval/map_metrics_checks.hpp, eval/voxel_checks.hpp):
/// by default each is a warning on stderr and a line of the summary's "problems"; with the
/// evaluation's `strict` parameter the first one is bad input (exit 3). docs/evaluate.md.
#include <string>
#include <vector>

namespace mapfuse::eval {

/// @brief Warns about each of `problems` (prefixed by `what`, e.g. "evaluate map") and appends
/// it to `noted`.
/// @throws InputError (exit 3) with the first problem when `strict`.
void warnOrRefuse(const std::vector<std::string>& problems, bool strict, const std::string& what,
                  std::vector<std::string>& noted);

}  // namespace mapfuse::eval
