#pragma once
/// @file Stage `info`: what a mapfuse file holds, as JSON (format, counts, frame, origin,
/// extent), and the shared ENU origin that per-drive georef jobs of one batch must agree on.
#include <filesystem>
#include <nlohmann/json.hpp>

#include "mapfuse/geo/origin.hpp"

namespace mapfuse::stages {

/// @brief Facts about an LSM, vector map, tiles manifest or summary file.
/// @throws IoError, ParseError (malformed file or unknown format).
nlohmann::json describeFile(const std::filesystem::path& path);

/// @brief The ENU origin an LSM implies: its own origin when georeferenced, else its first GPS
/// fix. @throws InputError when it has neither.
geo::GeoOrigin originOfLsm(const std::filesystem::path& path);

}  // namespace mapfuse::stages
