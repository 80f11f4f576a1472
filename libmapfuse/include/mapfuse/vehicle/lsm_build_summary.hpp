#pragma once
/// @file The counts and timings of buildLsm as lsm-build.summary.json holds them
/// (docs/lsm-build.md): VP calibration, body tilt, ego-motion against GPS, ranging, assembly,
/// aerial triangulation.
#include <nlohmann/json.hpp>

#include "mapfuse/vehicle/lsm_build.hpp"

namespace mapfuse::vehicle {

/// @brief buildLsm's result as the summary's JSON object (keys of docs/lsm-build.md).
nlohmann::json toJson(const LsmBuildResult& result);

}  // namespace mapfuse::vehicle
