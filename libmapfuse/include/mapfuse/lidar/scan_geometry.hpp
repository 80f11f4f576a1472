#pragma once
/// @file A truth-free geometric split of one LiDAR scan into ground, static structure and possible
/// road users (docs/lidar.md, "Odometry"). Ground: points within `ground_tolerance` of the lower
/// envelope of cones of slope `ground_slope` standing on the lowest return of every ground cell
/// within `ground_window` cells (terrain less steep stays ground). The other points are binned
/// in vertical columns (`column_cell` in x, y) and each column is cut into segments where the
/// points leave a vertical gap wider than `max_gap`. A segment is a possible road user when it
/// starts near the ground (at most `max_bottom` above it: a car's roof seen from above starts at
/// ~1.5 m) and ends at most `max_height` above it: cars, vans, buses, trucks, cyclists and
/// pedestrians, also when parked or queued bumper to bumper, and also under a bridge or a tree
/// (the bridge deck or the canopy is another segment). Static structure is what reaches higher
/// (building walls, poles, trees, bridge piers) or floats (decks, canopies): low static objects
/// (fences, hedges, parked cars) count as road users, which only costs the odometry some points.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "mapfuse/core/param.hpp"

namespace mapfuse::lidar {

struct SceneGeometrySettings {
  double ground_cell = 1.0;       ///< m, cell of the ground height grid
  int ground_window = 3;          ///< cells each side of the lowest-return filter
  double ground_tolerance = 0.3;  ///< m, points this close above the ground are ground
  double ground_slope = 0.3;      ///< steepest terrain that is still ground (rise over run)
  double column_cell = 0.5;       ///< m, x-y cell of the vertical columns
  double max_gap = 0.6;           ///< m, a wider vertical gap starts a new segment of a column
  double max_height = 4.3;        ///< m above ground, top of the tallest road user
  double max_bottom = 2.0;        ///< m above ground, highest start of a road user's segment

  static constexpr const char* kName = "SceneGeometrySettings";  ///< names the owner in messages
  template <class V>
  void visit(V& v) {
    using namespace param;
    v("ground_cell", ground_cell, "m", "cell of the ground height grid", gt(0));
    v("ground_window", ground_window, "", "cells each side of the lowest-return filter", in(0, 50));
    v("ground_tolerance", ground_tolerance, "m", "this close above the ground is ground", ge(0));
    v("ground_slope", ground_slope, "", "steepest ground (rise over run)", ge(0));
    v("column_cell", column_cell, "m", "x-y cell of the vertical columns", gt(0));
    v("max_gap", max_gap, "m", "a wider vertical gap starts a new segment", gt(0));
    v("max_height", max_height, "m", "top of the tallest road user above ground", gt(0));
    v("max_bottom", max_bottom, "m", "highest start of a road user's segment", ge(0));
  }
};

enum class ScanPointKind : uint8_t { kGround = 0, kStatic = 1, kRoadUser = 2 };

/// Counts of one split.
struct SceneGeometryStats {
  std::size_t ground = 0, static_points = 0, road_user = 0;
  std::size_t segments = 0, road_user_segments = 0;
};

/// @brief Splits the points of one scan (sensor frame, z up).
/// @param heights optional, receives every point's height above the ground (m)
/// @return one kind per point.
std::vector<ScanPointKind> splitScanGeometry(const std::vector<Eigen::Vector3d>& points,
                                             const SceneGeometrySettings& settings,
                                             SceneGeometryStats* stats = nullptr,
                                             std::vector<double>* heights = nullptr);

}  // namespace mapfuse::lidar
