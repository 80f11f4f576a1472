#pragma once
/// @file Aggregation of discrete elements (§4.3.1, Song et al. 2023): ground arrows and
/// crosswalks are clustered by DBSCAN with the rectangle intersection-over-union distance
/// (1 - IoU), traffic signs, poles and traffic lights by 3D distance, stop lines by midpoint
/// distance and direction; each cluster is merged by confidence-weighted averaging.
#include <Eigen/Core>
#include <vector>

#include "mapfuse/aggregate/observations.hpp"
#include "mapfuse/aggregate/settings.hpp"
#include "mapfuse/core/vector_map.hpp"

namespace mapfuse::aggregate {

/// @brief Four corners of an oriented rectangle fitted to a planar element (its own 4 points
/// when it has exactly 4, else the principal-axes bounding rectangle in its best-fit plane).
std::vector<Eigen::Vector3d> toRectangle(const std::vector<Eigen::Vector3d>& points);

/// @brief Intersection over union of two ground polygons in the EN plane (0 when disjoint).
double polygonIou2d(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b);

/// @brief Clusters and merges the observations `indices` (all of class `cls`, not lane lines)
/// into map instances (ids left 0, support filled, geometry per geometryKind(cls)). Each is
/// compared with those of at most `partner_drives` other drives (0 = all; partner_drives.hpp).
std::vector<MapInstance> mergeDiscrete(const std::vector<Observation>& items,
                                       const std::vector<std::size_t>& indices, CrowdClass cls,
                                       const DiscreteMergeParams& params, int num_drives,
                                       int partner_drives, std::size_t* noise = nullptr);

}  // namespace mapfuse::aggregate
