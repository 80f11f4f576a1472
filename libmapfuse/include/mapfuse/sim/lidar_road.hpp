#pragma once
/// @file The road of the synthetic LiDAR street (docs/lidar-ground-truth.md): a centreline
/// polyline (straights and circular turns) in the world frame (x east, y north, z up, metres),
/// a road surface at z = 0 with lane markings, raised sidewalks with curbs and terrain beyond.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace mapfuse::sim {

/// Cross-section of the street (all metres).
struct RoadProfile {
  double road_half_width = 5.0;   ///< m, centreline to curb
  double sidewalk_width = 3.0;    ///< m, curb to the property line
  double curb_height = 0.15;      ///< m, sidewalk and terrain height above the road
  double lane_width = 3.5;        ///< m, used for the ego lane and moving vehicles
  double dash_length = 3.0;       ///< m, centre-line dash
  double dash_gap = 6.0;          ///< m, gap between centre-line dashes
  double marking_width = 0.12;    ///< m, width of painted lines
  double edge_line_offset = 0.3;  ///< m, edge line inside the curb
};

/// Where a 2D point lies relative to the centreline.
struct RoadCoord {
  double s = 0.0;        ///< m, arc length of the closest centreline point
  double lateral = 0.0;  ///< m, signed distance, positive to the left of the driving direction
  bool near = false;     ///< false: farther than the query radius (lateral is then +-inf)
};

/// Class of the ground at a point.
enum class GroundKind : uint8_t { kRoad, kLaneMarking, kSidewalk, kTerrain };

/// The centreline with a coarse 2D grid for fast closest-segment queries.
class Road {
 public:
  /// @brief Builds the road from centreline samples (at least 2, spacing > 0).
  /// @param query_radius m, farthest lateral distance for which coordinates are computed.
  Road(std::vector<Eigen::Vector2d> centreline, RoadProfile profile, double query_radius);

  /// @brief Road coordinates of (x, y); `near` is false beyond the query radius.
  RoadCoord locate(double x, double y) const;
  /// @brief Point at arc length s (clamped to the road) and lateral offset (left positive).
  Eigen::Vector2d pointAt(double s, double lateral) const;
  /// @brief Heading (rad, from east, counter-clockwise) of the centreline at arc length s.
  double headingAt(double s) const;
  /// @brief Kind of ground at road coordinates.
  GroundKind groundAt(const RoadCoord& c) const;
  /// @brief Height (m) of the ground surface at road coordinates (0 on the road, curb above).
  double groundHeight(const RoadCoord& c) const;

  double length() const { return s_.back(); }  ///< m
  const RoadProfile& profile() const { return profile_; }
  const std::vector<Eigen::Vector2d>& centreline() const { return pts_; }

 private:
  std::vector<Eigen::Vector2d> pts_;
  std::vector<double> s_;
  RoadProfile profile_;
  double radius_;
  double cell_ = 4.0;
  Eigen::Vector2d min_;
  int nx_ = 0, ny_ = 0;
  std::vector<uint32_t> cell_start_, cell_items_;
};

/// @brief Centreline of a street: straight, turn, straight, turn, straight, sampled every
/// `spacing` metres. Straight lengths, turn radii and directions come from the caller.
std::vector<Eigen::Vector2d> makeCentreline(const std::vector<double>& straights,
                                            const std::vector<double>& turn_radii,
                                            const std::vector<double>& turn_angles, double spacing);

}  // namespace mapfuse::sim
