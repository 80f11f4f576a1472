#include "mapfuse/lidar/map_refinement.hpp"

#include "mapfuse/core/stopwatch.hpp"

namespace mapfuse::lidar {

MapRefinementResult refineMap(SemanticVoxelMap& map, const std::vector<Pose3>& T_map_velo,
                              const ScanSource& scans, const MapRefinementSettings& s,
                              const SensorReach& reach, int num_threads) {
  MapRefinementResult r;
  if (!s.enabled) return r;
  r.ran = true;
  auto removeVoxels = [&](const std::vector<uint8_t>& keep, bool trace) {
    for (std::size_t i = 0; i < keep.size(); ++i)
      if (!keep[i]) r.removed[map.voxels()[i].key] = {map.voxels()[i].label, trace};
    map.filter(keep);
  };
  Stopwatch t;
  const std::size_t before = map.size();
  removeVoxels(knnMeanDistanceFilter(map, s.knn, num_threads), false);  // §2.2, isolated voxels
  r.knn_removed_voxels = before - map.size();
  r.seconds_knn = t.seconds();
  if (s.remove_traces && s.seen_through) {
    t.restart();
    SeenThroughFilter seen(map, s.through, reach, num_threads);
    for (std::size_t i = 0; i < T_map_velo.size(); ++i) seen.addScan(scans(i), T_map_velo[i]);
    removeVoxels(seen.keepMask(&r.seen_through), true);
    r.ran_seen_through = true;
    r.seconds_seen_through = t.seconds();
  }
  if (s.remove_traces) {
    t.restart();
    removeVoxels(vehicleTraceFilter(map, s.traces, &r.traces), true);  // §2.2, eta_d and eta_l
    r.ran_traces = true;
    r.seconds_traces = t.seconds();
  }
  return r;
}

nlohmann::json refinementReport(const MapRefinementResult& r) {
  nlohmann::json j = {{"enabled", r.ran}};
  if (!r.ran) return j;
  j["knn_removed_voxels"] = r.knn_removed_voxels;
  if (r.ran_seen_through) {
    j["seen_through_tested_voxels"] = r.seen_through.tested_voxels;
    j["seen_through_removed_voxels"] = r.seen_through.removed_voxels;
  }
  if (r.ran_traces) {
    j["vehicle_voxels"] = r.traces.vehicle_voxels;
    j["vehicle_clusters"] = r.traces.clusters;
    j["trace_clusters_removed"] = r.traces.removed_clusters;
    j["trace_voxels_removed"] = r.traces.removed_voxels;
  }
  return j;
}

}  // namespace mapfuse::lidar
