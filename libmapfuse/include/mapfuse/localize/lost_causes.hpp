#pragma once
/// @file Why keyframes were lost (issue 35, docs/localize.md "Lost keyframes"). A keyframe is
/// lost when fewer than `min_matches` of its observed points match the map. Two causes differ
/// for the user: the drive observed fewer than `min_matches` points in its window (a road
/// without painted lines: no markings to match, whatever the map), or it observed enough but
/// the map held too few near them (outside the map, or a map that does not match the road).
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "mapfuse/localize/localizer.hpp"

namespace mapfuse::localize {

struct LostCauses {
  std::size_t no_markings = 0;  ///< lost with fewer than min_matches observed points
  std::size_t outside_map = 0;  ///< lost with enough observed points that the map did not match
};

/// @brief The causes of the lost keyframes of `result`.
LostCauses lostCauses(const LocalizeResult& result, int min_matches);

/// @brief One sentence naming each drive (`file`, its result) with lost keyframes and the
/// causes, e.g. "a.cbor: 53 of 159 keyframes lost (53 no markings to match: too few observed
/// points, a road without painted lines?; 0 outside the map)".
std::string lostDiagnosis(const std::vector<std::pair<std::string, const LocalizeResult*>>& drives,
                          int min_matches);

}  // namespace mapfuse::localize
