#include "mapfuse/lidar/semantic_mapper.hpp"

#include <future>

#include "forest_source.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/core/progress.hpp"
#include "mapfuse/core/stopwatch.hpp"
#include "mapfuse/io/velodyne.hpp"

namespace mapfuse::lidar {
namespace {
double bytesPerVoxel(const SemanticVoxelMap& map) {
  return map.empty() ? 0.0
                     : static_cast<double>(map.memoryBytes()) / static_cast<double>(map.size());
}

/// One frame's inputs, read (and segmented) ahead of its fusion.
struct FrameInput {
  io::VelodyneScan scan;
  io::SemanticImage sem;
  double t_load = 0, t_semantics = 0;  ///< s, in the reading thread
};

/// §2.1: every frame labelled and fused into `r.map` (eq. 2-6). Frame k+1 is read and segmented
/// (ENet, the expensive part) in a second thread while frame k is projected, filtered and fused,
/// so that network and LiDAR work overlap; the fusion order, hence the map, is unchanged.
void fuseFrames(const io::KittiRawDrive& drive, FrameSemantics& semantics,
                const ClusterClassifier& classifier, const FrameFusionSettings& settings,
                SemanticMapResult& r) {
  const ImageProjection camera = ImageProjection::of(drive.calib);
  auto read = [&](std::size_t i) {  // one call at a time: semantics is not shared otherwise
    FrameInput in;
    Stopwatch t;
    in.scan = io::readVelodyneBin(drive.frames[i].velodyne);
    in.t_load = t.seconds();
    t.restart();
    in.sem = semantics.get(drive.frames[i]);
    in.t_semantics = t.seconds();
    return in;
  };
  Progress progress("frames", drive.frames.size());
  std::future<FrameInput> next;
  if (!drive.frames.empty()) next = std::async(std::launch::async, read, 0);
  for (std::size_t i = 0; i < drive.frames.size(); ++i) {
    Stopwatch wait;
    const FrameInput in = next.get();  // rethrows the reader's error
    r.timings.wait_inputs += wait.seconds();
    if (i + 1 < drive.frames.size()) next = std::async(std::launch::async, read, i + 1);
    r.timings.load_scans += in.t_load;
    r.timings.semantics += in.t_semantics;
    const auto st = fuseFrame(r.map, in.scan.points, r.poses.T_map_velo[i], camera, in.sem,
                              classifier, settings);
    r.timings.projection += st.t_projection;
    r.timings.error_minimization += st.t_error_min;
    r.timings.fusion += st.t_fusion;
    r.points_projected += st.projected;
    r.points_fused += st.fused_points;
    r.error_min.clusters += st.error_min.clusters;
    r.error_min.rejected_clusters += st.error_min.rejected_clusters;
    r.error_min.rejected_points += st.error_min.rejected_points;
    progress.advance();
  }
  progress.finish();
}
}  // namespace

SemanticMapResult buildSemanticMap(const io::KittiRawDrive& drive, const SemanticMapSettings& s,
                                   const std::filesystem::path& semantics_cache) {
  SemanticMapResult r;
  Stopwatch t;
  const FrameFusionSettings& fusion = s.fusion;
  FrameSemantics semantics(drive, s.semantics, semantics_cache);  // first: refuses imageless drives
  ForestSource forests = loadForests(s.classifier_dir);
  const ClusterClassifier& classifier = forests.classifier;
  r.timings.open = t.seconds();

  t.restart();
  r.poses = drivePoses(drive, s.poses);
  r.timings.poses = t.seconds();

  r.map = SemanticVoxelMap(s.voxel_size, static_cast<float>(s.min_log_prob));
  Stopwatch fusing;
  fuseFrames(drive, semantics, classifier, fusion, r);
  r.timings.frames = fusing.seconds();
  r.voxels_after_fusion = r.map.size();
  r.bytes_per_voxel_before_shrink = bytesPerVoxel(r.map);
  r.map.shrinkToFit();
  r.bytes_per_voxel = bytesPerVoxel(r.map);

  r.semantics = {semantics.source(), semantics.fromPrecomputed(), semantics.fromCache(),
                 semantics.fromNetwork(), semantics.networkSeconds()};
  r.forest_labels = classifier.labels();
  for (const std::string& name : r.forest_labels)
    r.forest_thresholds[name] = classifier.threshold(*lidarClassFromName(name));
  r.classifier_dir = forests.dir.string();
  r.forest_provenance = forests.provenance;
  r.error_min_skipped = forests.skipped;
  if (!r.error_min_skipped.empty())
    MAPFUSE_INFO("lidar-semantic-map: error minimisation skipped (" << r.error_min_skipped << ")");

  // one range and thread count for the run: the projection's
  const SensorReach reach{s.fusion.projection.min_range, s.fusion.projection.max_range};
  r.refinement = refineMap(
      r.map, r.poses.T_map_velo,
      [&](std::size_t i) { return io::readVelodyneBin(drive.frames[i].velodyne).points; },
      s.refinement, reach, s.num_threads);
  return r;
}

}  // namespace mapfuse::lidar
