#pragma once
/// @file Human-readable outputs of `evaluate map`: a Markdown report with tables shaped like
/// Table 1 / Table 3 of Song et al. 2023, and PNG plots (error per class; error versus the
/// number of traversals when several maps are evaluated).
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "mapfuse/eval/map_metrics.hpp"
#include "mapfuse/eval/trajectory_metrics.hpp"

namespace mapfuse::eval {

/// One evaluated map.
struct MapReportEntry {
  std::string name;    ///< file name shown in the report
  int traversals = 0;  ///< drives aggregated into the map (0 = unknown)
  MapMetrics metrics;
};

/// @brief Markdown: one per-class table per map, relative-precision- and
/// completeness-versus-traversals tables when there are several maps, and a trajectory table
/// when `trajectories` is not empty.
std::string markdownReport(const std::vector<MapReportEntry>& maps,
                           const std::vector<TrajectoryMetrics>& trajectories);

/// @brief Bar chart: relative precision and mean absolute error per class (m).
void writeErrorPerClassPng(const std::filesystem::path& path, const MapReportEntry& entry);

/// @brief Line charts (Fig. 9, Song et al. 2023), one above the other: relative precision (m) and
/// completeness of each class versus the number of traversals.
void writeErrorVsTraversalsPng(const std::filesystem::path& path,
                               const std::vector<MapReportEntry>& maps);

}  // namespace mapfuse::eval
