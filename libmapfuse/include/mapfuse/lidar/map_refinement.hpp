#pragma once
/// @file Batch refinement of a semantic voxel map (Jeong et al. 2018, §2.2; docs/lidar.md): the
/// K-nearest-voxel filter, then the moving-vehicle traces: voxels other scans see through
/// (lidar/seen_through_filter.hpp) and the paper's size rules on DBSCAN clusters of vehicle
/// voxels (lidar/refinement.hpp). The voxels taken out keep their labels for the scan labels.
#include <Eigen/Core>
#include <functional>
#include <nlohmann/json.hpp>
#include <vector>

#include "mapfuse/core/param.hpp"
#include "mapfuse/core/se3.hpp"
#include "mapfuse/lidar/map_export.hpp"
#include "mapfuse/lidar/refinement.hpp"
#include "mapfuse/lidar/seen_through_filter.hpp"

namespace mapfuse::lidar {

struct MapRefinementSettings {
  bool enabled = true;          ///< run the batch refinement at all
  KnnFilterSettings knn;        ///< isolated voxels
  bool remove_traces = true;    ///< remove moving-vehicle traces
  VehicleTraceSettings traces;  ///< size rules (eta_d, eta_l)
  bool seen_through = true;     ///< also the free-space test
  SeenThroughSettings through;  ///< free-space test

  template <class V>
  void visit(V& v) {
    v("refine", enabled, "", "run the batch refinement");
    knn.visit(v);
    v("remove_vehicle_traces", remove_traces, "", "remove moving-vehicle traces");
    traces.visit(v);
    v("trace_seen_through", seen_through, "",
      "also drop voxels that other scans see through (free-space test)");
    through.visit(v);
  }
};

/// What refinement did; a step that did not run leaves its `ran_` flag false.
struct MapRefinementResult {
  bool ran = false;  ///< settings.enabled
  std::size_t knn_removed_voxels = 0;
  bool ran_seen_through = false;
  SeenThroughStats seen_through;
  bool ran_traces = false;
  VehicleTraceStats traces;
  RemovedVoxelLabels removed;  ///< out of the map, still labelled in the scans
  double seconds_knn = 0, seconds_seen_through = 0, seconds_traces = 0;  ///< s
};

/// The scan of frame i in its sensor frame (the free-space test reads every scan once more).
using ScanSource = std::function<std::vector<Eigen::Vector3f>(std::size_t i)>;

/// @brief Refines `map` in place.
/// @param T_map_velo pose of every scan, indexed like `scans`
/// @param reach the range over which scans see through voxels (the run's projection range)
/// @param num_threads OpenMP threads (results do not depend on it)
MapRefinementResult refineMap(SemanticVoxelMap& map, const std::vector<Pose3>& T_map_velo,
                              const ScanSource& scans, const MapRefinementSettings& settings,
                              const SensorReach& reach, int num_threads);

/// @brief What refinement did, for the summary: voxels each step removed (only the steps that
/// ran).
nlohmann::json refinementReport(const MapRefinementResult& result);

}  // namespace mapfuse::lidar
