#pragma once
/// @file What `evaluate map` can know makes its scores meaningless (docs/evaluate.md "Inputs
/// that cannot be scored"): an empty truth, an empty map, or a map and a truth whose extents do
/// not overlap (another frame or origin: a truth 2 km away scores completeness 0 everywhere,
/// which reads as a bad map, not as a wrong input). Each problem is one sentence naming the file.
#include <string>
#include <vector>

#include "mapfuse/core/vector_map.hpp"

namespace mapfuse::eval {

/// A map and a truth whose xy extents, each grown by this, do not meet do not overlap [m]. Far
/// above the match tolerances (<= 100 m), far below the 2 km of a wrong origin.
inline constexpr double kOverlapMargin = 100.0;

/// @brief The problems of scoring `map` (already in the truth's ENU) against `truth`.
/// @return empty when the evaluation can mean something.
std::vector<std::string> mapEvaluationProblems(const VectorMap& map, const std::string& map_file,
                                               const VectorMap& truth,
                                               const std::string& truth_file);

}  // namespace mapfuse::eval
