#pragma once
/// @file The outline of an area marking (crosswalk, arrow) from its observations over several
/// frames (issue 21). A minimum-area rectangle turned a skewed crosswalk (a parallelogram where a
/// road meets a junction at an angle) into a rotated rectangle metres off at two corners. The
/// outline is kept instead: when frames saw the whole polygon with one vertex count (the corners
/// of an observation list: the simulator, a detector's polygons) those corners are averaged
/// vertex by vertex (aligned by cyclic shift and reversal); otherwise (mask components, partial
/// views) the convex hull of every observed point is reduced to `max_vertices` vertices by
/// dropping the vertex whose triangle with its neighbours is smallest (Visvalingam-Whyatt).
#include <Eigen/Core>
#include <vector>

namespace mapfuse {

/// @brief Convex hull of points in the x-y plane (Andrew's monotone chain), counter-clockwise,
/// without repeated vertices; z of each hull vertex kept.
std::vector<Eigen::Vector3d> convexHullXy(const std::vector<Eigen::Vector3d>& points);

/// @brief Drops the vertex of least triangle area (x-y) until `max_vertices` remain.
std::vector<Eigen::Vector3d> simplifyRing(std::vector<Eigen::Vector3d> ring,
                                          std::size_t max_vertices);

/// @brief `c` cyclically shifted (and reversed when better) to match `ref` vertex by vertex
/// (least squared distances); both of one size.
std::vector<Eigen::Vector3d> alignRing(const std::vector<Eigen::Vector3d>& ref,
                                       const std::vector<Eigen::Vector3d>& c);

/// @brief The parallelogram through three of its corners: the fourth is added opposite the
/// corner of the widest angle (a + c - b): right for rectangles and mild skews; three corners
/// of a strongly skewed one (60 deg) fit another parallelogram better. Other sizes are returned
/// unchanged.
std::vector<Eigen::Vector3d> completeParallelogram(const std::vector<Eigen::Vector3d>& tri);

/// @brief The outline of one area marking from its per-frame observations (each a ring, the
/// points ranged in the frame): the vertex-wise mean of the observations that have the most
/// common vertex count (>= 3; only `corner_count` when > 0: a ring missing a corner that fell
/// out of the range band is partial) when at least `min_complete` do and they agree (median
/// over them of the largest vertex distance to the mean <= max_corner_spread, m), else the
/// simplified convex hull of all points (at most `max_vertices` vertices). With corner_count 4
/// (a crosswalk, a parallelogram) a hull that is a triangle (one corner never seen) is
/// completed by completeParallelogram.
std::vector<Eigen::Vector3d> areaOutline(const std::vector<std::vector<Eigen::Vector3d>>& rings,
                                         int min_complete, std::size_t max_vertices,
                                         double max_corner_spread = 0.5,
                                         std::size_t corner_count = 0);

}  // namespace mapfuse
