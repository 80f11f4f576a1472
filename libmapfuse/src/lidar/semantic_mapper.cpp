#include "mapfuse/lidar/semantic_mapper.hpp"

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

/// §2.1: every frame labelled and fused into `r.map` (eq. 2-6).
void fuseFrames(const io::KittiRawDrive& drive, FrameSemantics& semantics,
                const ClusterClassifier& classifier, const FrameFusionSettings& settings,
                SemanticMapResult& r) {
  const Eigen::Matrix<double, 3, 4> P = drive.calib.veloToImage2();
  Progress progress("frames", drive.frames.size());
  for (std::size_t i = 0; i < drive.frames.size(); ++i) {
    const auto& f = drive.frames[i];
    Stopwatch t;
    const io::VelodyneScan scan = io::readVelodyneBin(f.velodyne);
    r.timings.load_scans += t.seconds();
    t.restart();
    const io::SemanticImage sem = semantics.get(f);
    r.timings.semantics += t.seconds();
    const auto st =
        fuseFrame(r.map, scan.points, r.poses.T_map_velo[i], P, sem, classifier, settings);
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

FrameFusionSettings fusionForDrive(FrameFusionSettings fusion, const io::KittiRawDrive& drive) {
  fusion.projection.image_width = drive.calib.image_width;
  fusion.projection.image_height = drive.calib.image_height;
  return fusion;
}

SemanticMapResult buildSemanticMap(const io::KittiRawDrive& drive, const SemanticMapSettings& s,
                                   const std::filesystem::path& semantics_cache) {
  SemanticMapResult r;
  Stopwatch t;
  const FrameFusionSettings fusion = fusionForDrive(s.fusion, drive);
  ClusterClassifier classifier;
  if (!s.classifier_dir.empty()) classifier = ClusterClassifier::load(s.classifier_dir);
  FrameSemantics semantics(drive, s.semantics, semantics_cache);
  r.timings.open = t.seconds();

  t.restart();
  r.poses = drivePoses(drive, s.poses);
  r.timings.poses = t.seconds();

  r.map = SemanticVoxelMap(s.voxel_size, static_cast<float>(s.min_log_prob));
  fuseFrames(drive, semantics, classifier, fusion, r);
  r.voxels_after_fusion = r.map.size();
  r.bytes_per_voxel_before_shrink = bytesPerVoxel(r.map);
  r.map.shrinkToFit();
  r.bytes_per_voxel = bytesPerVoxel(r.map);

  r.semantics = {semantics.source(), semantics.fromPrecomputed(), semantics.fromCache(),
                 semantics.fromNetwork(), semantics.networkSeconds()};
  r.forest_labels = classifier.labels();
  if (classifier.empty()) {
    r.error_min_skipped = s.classifier_dir.empty() ? "no classifier_dir given"
                                                   : "no rtrees_<label>.yml in classifier_dir";
    MAPFUSE_INFO("lidar-semantic-map: error minimisation skipped (" << r.error_min_skipped << ")");
  }

  MapRefinementSettings refinement = s.refinement;  // one range and thread count for the run
  refinement.knn.num_threads = refinement.through.num_threads = s.num_threads;
  refinement.through.min_range = s.fusion.projection.min_range;
  refinement.through.max_range = s.fusion.projection.max_range;
  r.refinement = refineMap(
      r.map, r.poses.T_map_velo,
      [&](std::size_t i) { return io::readVelodyneBin(drive.frames[i].velodyne).points; },
      refinement);
  return r;
}

}  // namespace mapfuse::lidar
