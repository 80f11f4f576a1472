#pragma once
/// @file Batch map refinement (Jeong et al. 2018, §2.2): a K-nearest-voxel mean-distance
/// filter that removes isolated voxels, and removal of the traces moving vehicles leave, found
/// by DBSCAN on the 2D (x, y) projection of the vehicle voxels.
#include <cstdint>
#include <vector>

#include "mapfuse/core/param.hpp"

#include "mapfuse/lidar/voxel_map.hpp"

namespace mapfuse::lidar {

struct KnnFilterSettings {
  int k = 6;  ///< neighbours K
  double max_mean_distance =
      0.20;  ///< delta_d, m: voxels whose K nearest are farther on average go

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("knn_k", k, "", "K of the K-nearest-voxel filter", in(1, 32));
    v("knn_max_mean_distance", max_mean_distance, "m", "delta_d of the K-nearest-voxel filter",
      gt(0) & le(100));
  }
};

/// @brief Keep mask: 1 when the mean distance from the voxel centre to its K nearest other voxel
/// centres is <= delta_d. Exact K-nearest search over growing cube shells (Chebyshev distance
/// r = 1, 2, ... up to ceil(K delta_d / voxel size) + 1), stopping as soon as the result is
/// decided (all unvisited voxels are farther than the shell); voxels still open at the last shell
/// are dropped. Runs over the keys sorted in (x, y, z) order (12-24 bytes per voxel while it
/// runs). @throws InputError when k is outside 1..32 or max_mean_distance <= 0.
/// @param num_threads OpenMP threads (results do not depend on it)
std::vector<uint8_t> knnMeanDistanceFilter(const SemanticVoxelMap& map, const KnnFilterSettings& s,
                                           int num_threads = 1);

struct VehicleTraceSettings {
  double eps = 0.25;   ///< DBSCAN radius on the (x, y) plane, m
  int min_points = 5;  ///< DBSCAN core threshold (2D cells, including the cell itself)
  /// eta_d: clusters with more vehicle voxels are traces (paper: 500, for its coarser voxels;
  /// docs/lidar.md)
  std::size_t max_voxels = 100000;
  double max_length = 10.0;  ///< eta_l, m: clusters longer than this (principal axis) are traces

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("trace_eps", eps, "m", "DBSCAN radius on the 2D vehicle projection", gt(0) & le(100));
    v("trace_min_points", min_points, "", "DBSCAN minimum points (2D cells)", in(1, 1e9));
    v("trace_max_voxels", max_voxels, "", "eta_d: clusters with more vehicle voxels are traces",
      in(1, 1e9));
    v("trace_max_length", max_length, "m", "eta_l: clusters longer than this are traces",
      gt(0) & le(10000));
  }
};

struct VehicleTraceStats {
  std::size_t vehicle_voxels = 0;
  std::size_t clusters = 0;
  std::size_t removed_clusters = 0;
  std::size_t removed_voxels = 0;
};

/// @brief Keep mask: 0 for vehicle voxels in DBSCAN clusters with > max_voxels voxels or longer
/// than max_length; all other voxels (and DBSCAN noise) are kept.
std::vector<uint8_t> vehicleTraceFilter(const SemanticVoxelMap& map, const VehicleTraceSettings& s,
                                        VehicleTraceStats* stats);

}  // namespace mapfuse::lidar
