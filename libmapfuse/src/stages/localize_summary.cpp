// localize.summary.json of a localize run (docs/localize.md "Outputs"): per drive the counts
// and errors, over all drives the paper's three averages, the map's frame and the lost share.
#include "mapfuse/localize/report.hpp"
#include "mapfuse/stages/localize.hpp"

namespace mapfuse::stages {

nlohmann::json toJson(const LocalizeRun& run) {
  nlohmann::json drives = nlohmann::json::array();
  std::vector<localize::LocalizeErrors> errors;
  for (const auto& d : run.drives) {
    nlohmann::json j = localize::toJson(d.result);
    j["drive_id"] = d.drive_id;
    j["file"] = d.file;
    if (d.errors) {
      j["localized"] = localize::toJson(d.errors->localized);
      j["prior"] = localize::toJson(d.errors->prior);
      if (d.map_to_truth) j["localized_in_map_frame"] = localize::toJson(d.errors->in_map);
      errors.push_back(*d.errors);
    }
    drives.push_back(j);
  }
  nlohmann::json s = {
      {"level", run.level},
      {"solve", run.solve},
      {"drives", drives},
      {"keyframes", run.keyframes},
      {"lost", run.lost},
      {"lost_share", run.lostShare()},
      {"seconds_localize", run.seconds_localize},
      {"localisations_per_second_per_core",
       run.seconds_localize > 0 ? double(run.keyframes) / run.seconds_localize : 0.0}};
  if (!errors.empty()) {  // the paper's three averages, over all drives' localised keyframes
    using localize::ErrorOf;
    s["localized"] = localize::toJson(localize::pooled(errors, ErrorOf::kLocalized));
    s["prior"] = localize::toJson(localize::pooled(errors, ErrorOf::kPrior));
    // the drives share the map: their mean ENU error is the map's offset against the truth
    const Eigen::Vector2d offset = localize::commonOffset(errors);
    s["common_offset_enu_m"] = {offset.x(), offset.y()};
    s["localized_without_common_offset"] =
        localize::toJson(localize::pooledWithoutOffset(errors, offset));
    if (!run.drives.empty() && run.drives.front().map_to_truth) {
      // (b) the truth carried into the map's frame by the rigid map-to-truth transform
      const localize::MapToTruth& m = *run.drives.front().map_to_truth;
      s["map_to_truth"] = {{"dx_m", m.dx},
                           {"dy_m", m.dy},
                           {"yaw_deg", m.yaw_deg},
                           {"points", m.points},
                           {"matched", m.matched},
                           {"rms_before_m", m.rms_before},
                           {"rms_after_m", m.rms_after}};
      s["localized_in_map_frame"] = localize::toJson(localize::pooled(errors, ErrorOf::kInMap));
    }
  }
  return s;
}

}  // namespace mapfuse::stages
