#pragma once
/// @file The vector map as localisation targets (docs/localize.md): line segments of lane and
/// stop lines, and reference points of the discrete elements (pole / light base, planar
/// centroid), each under a match key (class, and the lane-line attributes when they count), in a
/// uniform 2D grid so that a query reads only the cells around it (never the whole map).
#include <Eigen/Core>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "mapfuse/core/classes.hpp"
#include "mapfuse/core/vector_map.hpp"

namespace mapfuse::localize {

/// What an observed point is compared with: a map point or a map line segment.
struct MapTarget {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();  ///< ENU m: the point, or the segment start
  Eigen::Vector2d b = Eigen::Vector2d::Zero();  ///< ENU m: the segment end (== a for a point)
  bool is_line = false;
};

/// The nearest target of a query.
struct TargetMatch {
  const MapTarget* target = nullptr;  ///< nullptr: none within the radius
  double distance = 0.0;              ///< m, horizontal
};

/// @brief Match key of a class (and, for lane lines with `use_attributes`, its style and colour):
/// observations only match map targets under the same key.
int matchKey(CrowdClass cls, const Attributes& attributes, bool use_attributes);

/// @brief Horizontal distance of `p` to a target (point or segment), m.
double targetDistance(const MapTarget& t, const Eigen::Vector2d& p);

/// Grid over the map's targets (2D, ENU).
class MapIndex {
 public:
  /// @brief Indexes `map`: line instances as segments of their polylines, point instances by
  /// their base, planar instances by their centre. @param cell grid cell edge (m, > 0).
  MapIndex(const VectorMap& map, bool use_attributes, double cell = 4.0);

  /// @brief The nearest target under `key` within `radius` (m) of `p`.
  TargetMatch nearest(int key, const Eigen::Vector2d& p, double radius) const;

  std::size_t targets() const { return targets_.size(); }  ///< number of targets
  bool useAttributes() const { return use_attributes_; }

 private:
  int64_t cellKey(int key, int64_t ix, int64_t iy) const;
  void insert(int key, const MapTarget& t);

  double cell_;
  bool use_attributes_;
  std::vector<MapTarget> targets_;
  std::unordered_map<int64_t, std::vector<uint32_t>> cells_;  ///< cell key -> target indices
};

}  // namespace mapfuse::localize
