#pragma once
/// @file Stage `update` (docs/update.md, issue 34, first part): an existing vector map and new
/// drives' LSMs in the map's ENU frame -> the change report (mapfuse.map_changes with confidence
/// and supporting traversals), changes.geojson and update.{config,summary}.json. The updated map
/// itself is not written yet (docs/update.md "Not yet").
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mapfuse/update/change_detection.hpp"

namespace mapfuse::stages {

struct UpdateParams {
  static constexpr const char* kName = "UpdateParams";
  update::UpdateSettings detection;

  template <class V>
  void visit(V& v) {
    detection.visit(v);
  }
};

/// @brief The summary: counts per change kind, elements in view, confirmed, undecided, not
/// verified (count and ids), traversals, observations used, the registration per stretch of
/// each new drive (`inputs` name the drives).
nlohmann::json toJson(const update::UpdateResult& result, const std::vector<std::string>& inputs);

/// @brief Reads `map` and the LSMs, detects the changes and writes changes.json,
/// changes.geojson, update.config.json and update.summary.json into `out_dir` (all or none).
/// @throws ConfigError, IoError (exit 4), ParseError / InputError (exit 3: frame odom, origin
/// differs from the map's, no input).
update::UpdateResult runUpdate(const std::filesystem::path& map,
                               const std::vector<std::string>& inputs,
                               const std::filesystem::path& out_dir, const UpdateParams& params);

}  // namespace mapfuse::stages
