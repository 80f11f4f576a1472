#pragma once
/// @file What `localize` writes about a localisation (docs/localize.md "Outputs"): the localised
/// trajectory in the project's trajectory format (mapfuse.trajectory, as simulate's truth, with a
/// status per pose), the per-keyframe error table (CSV), the error-vs-distance plot (PNG) and
/// the summary fields.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "mapfuse/core/lat_lon_alt.hpp"
#include "mapfuse/localize/localizer.hpp"
#include "mapfuse/localize/truth_errors.hpp"

namespace mapfuse::localize {

/// @brief The localised keyframe poses as a `mapfuse.trajectory` document (readable by
/// eval::readTrueTrajectory); each pose also carries "status" (ok / lost) and "matches".
nlohmann::json trajectoryJson(const LocalizeResult& result, const std::string& drive_id,
                              const std::string& vehicle_id, const geo::GeoOrigin& origin);

/// @brief One CSV line per keyframe: id, distance_m, status, lateral_m, longitudinal_m,
/// heading_deg and the prior's three errors.
std::string errorsCsv(const LocalizeErrors& errors);

/// @brief Absolute lateral / longitudinal error (m, upper panel) and heading error (deg, lower
/// panel) of the localised poses against travelled distance (m), lost keyframes marked in red.
/// @throws IoError when the PNG cannot be written.
void writeErrorPlot(const std::filesystem::path& path, const LocalizeErrors& errors,
                    const std::string& title);

nlohmann::json toJson(const MeanAbsError& m);
/// @brief Counts of a drive's localisation (keyframes, lost, lost share, acquisitions, rate).
nlohmann::json toJson(const LocalizeResult& r);

}  // namespace mapfuse::localize
