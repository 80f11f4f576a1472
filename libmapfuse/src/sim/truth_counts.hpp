#pragma once
/// @file The element counts every map-based world builder (Lanelet2, OpenDRIVE) reports in
/// world.stats, and so in simulate's summary, under the same keys.
#include <map>
#include <string>

namespace mapfuse::sim::detail {

struct TruthCounts {
  int lane_lines = 0;          ///< lane-line elements of the truth
  int stop_lines = 0;          ///< stop lines
  int traffic_signs = 0;       ///< signs
  int traffic_lights = 0;      ///< lights
  int poles_mapped = 0;        ///< poles the map holds
  int poles_placed = 0;        ///< poles the simulator placed under signs and lights
  int line_pieces_joined = 0;  ///< marking pieces joined into one line

  void writeTo(std::map<std::string, double>& stats) const {
    stats["lane_lines"] = lane_lines;
    stats["stop_lines"] = stop_lines;
    stats["traffic_signs"] = traffic_signs;
    stats["traffic_lights"] = traffic_lights;
    stats["poles_mapped"] = poles_mapped;
    stats["poles_placed"] = poles_placed;
    stats["line_pieces_joined"] = line_pieces_joined;
  }
};

/// @brief The sum of a tally by kind (e.g. skipped way types).
inline int totalOf(const std::map<std::string, int>& tally) {
  int n = 0;
  for (const auto& kv : tally) n += kv.second;
  return n;
}

}  // namespace mapfuse::sim::detail
