#pragma once
/// @file Aggregation of discrete elements (§4.3.1, Song et al. 2023): ground arrows and
/// crosswalks are clustered by DBSCAN with the rectangle intersection-over-union distance
/// (1 - IoU), traffic signs, poles and traffic lights by 3D distance, stop lines by midpoint
/// distance and direction; each cluster is merged by confidence-weighted averaging.
#include <Eigen/Core>
#include <vector>

#include "mapfuse/aggregate/observations.hpp"
#include "mapfuse/core/vector_map.hpp"

namespace mapfuse::aggregate {

struct DiscreteMergeParams {
  double min_iou = 0.2;             ///< arrows, crosswalks: eps = 1 - min_iou on 1 - IoU
  double sign_radius = 1.0;         ///< m, traffic signs: eps on 3D centroid distance
  double point_radius = 1.0;        ///< m, poles and lights: eps on 3D base distance
  double stop_line_radius = 1.5;    ///< m, stop lines: eps on midpoint-to-segment distance
  double stop_line_angle_deg = 20;  ///< deg, stop lines: largest direction difference
  int min_pts = 3;                  ///< DBSCAN MinPts (capped by the number of drives)
  int partner_drives = 4;  ///< an element is compared with those of <= this many other drives
};

/// @brief Four corners of an oriented rectangle fitted to a planar element (its own 4 points
/// when it has exactly 4, else the principal-axes bounding rectangle in its best-fit plane).
std::vector<Eigen::Vector3d> toRectangle(const std::vector<Eigen::Vector3d>& points);

/// @brief Intersection over union of two ground polygons in the EN plane (0 when disjoint).
double polygonIou2d(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b);

/// @brief Clusters and merges the observations `indices` (all of class `cls`, not lane lines)
/// into map instances (ids left 0, support filled, geometry per geometryKind(cls)).
std::vector<MapInstance> mergeDiscrete(const std::vector<Observation>& items,
                                       const std::vector<std::size_t>& indices, CrowdClass cls,
                                       const DiscreteMergeParams& params, int num_drives,
                                       std::size_t* noise = nullptr);

}  // namespace mapfuse::aggregate
