#include "mapfuse/localize/lost_causes.hpp"

namespace mapfuse::localize {

LostCauses lostCauses(const LocalizeResult& result, int min_matches) {
  LostCauses c;
  for (const auto& k : result.keyframes) {
    if (k.status != KeyframeStatus::kLost) continue;
    if (k.observed < min_matches)
      ++c.no_markings;
    else
      ++c.outside_map;
  }
  return c;
}

std::string lostDiagnosis(const std::vector<std::pair<std::string, const LocalizeResult*>>& drives,
                          int min_matches) {
  std::string text;
  for (const auto& [file, result] : drives) {
    if (result->lost == 0) continue;
    const LostCauses c = lostCauses(*result, min_matches);
    if (!text.empty()) text += "; ";
    text += file + ": " + std::to_string(result->lost) + " of " +
            std::to_string(result->keyframes.size()) + " keyframes lost (" +
            std::to_string(c.no_markings) +
            " no markings to match: fewer observed points than min_matches, a road without "
            "painted lines?; " +
            std::to_string(c.outside_map) +
            " outside the map: observed points the map does not "
            "hold near the drive)";
  }
  return text;
}

}  // namespace mapfuse::localize
