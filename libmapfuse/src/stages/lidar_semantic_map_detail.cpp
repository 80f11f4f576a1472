#include "mapfuse/stages/lidar_semantic_map_detail.hpp"

#include "mapfuse/core/paths.hpp"

namespace mapfuse::stages::detail {

lidar::FrameFusionSettings fusionSettings(const LidarSemanticMapParams& p,
                                          const io::KittiRawDrive& drive) {
  lidar::FrameFusionSettings s;
  s.projection.min_range = p.min_range;
  s.projection.max_range = p.max_range;
  s.projection.image_width = drive.calib.image_width;
  s.projection.image_height = drive.calib.image_height;
  s.pixel.label_confidence = static_cast<float>(p.label_confidence);
  s.pixel.min_probability = static_cast<float>(p.min_probability);
  s.clustering.tolerance = p.cluster_tolerance;
  s.clustering.min_points = p.cluster_min_points;
  return s;
}

lidar::FrameSemanticsSettings semanticsSettings(const LidarSemanticMapParams& p,
                                                const std::filesystem::path& cache_dir) {
  lidar::FrameSemanticsSettings s;
  s.segmenter = p.segmenter;
  s.model = p.model.empty() ? sharedRoot() / "models/enet-cityscapes/enet-model.net"
                            : std::filesystem::path(p.model);
  s.enet.scale = p.enet_scale;
  s.precomputed_dir = p.semantics_dir;
  s.cache_dir = cache_dir;
  return s;
}

lidar::RTreesSettings rtreesSettings(const LidarSemanticMapParams& p) {
  lidar::RTreesSettings s;
  s.max_depth = p.rtrees_max_depth;
  s.num_trees = p.rtrees_trees;
  s.min_samples_per_class = p.rtrees_min_samples;
  s.seed = p.seed;
  return s;
}

lidar::KnnFilterSettings knnSettings(const LidarSemanticMapParams& p) {
  lidar::KnnFilterSettings s;
  s.k = p.knn_k;
  s.max_mean_distance = p.knn_max_mean_distance;
  s.num_threads = p.num_threads;
  return s;
}

lidar::VehicleTraceSettings traceSettings(const LidarSemanticMapParams& p) {
  lidar::VehicleTraceSettings s;
  s.eps = p.trace_eps;
  s.min_points = p.trace_min_points;
  s.max_voxels = static_cast<std::size_t>(p.trace_max_voxels);
  s.max_length = p.trace_max_length;
  return s;
}

lidar::SeenThroughSettings seenThroughSettings(const LidarSemanticMapParams& p) {
  lidar::SeenThroughSettings s;
  s.margin = p.seen_through_margin;
  s.window = p.seen_through_window;
  s.window_thin = p.seen_through_window_thin;
  s.num_threads = p.num_threads;
  s.min_range = p.min_range;
  s.max_range = p.max_range;
  s.min_seen_through = p.seen_through_min_scans;
  s.min_free_ratio = p.seen_through_min_ratio;
  s.vehicle_vote_radius = p.seen_through_vote_radius;
  s.vehicle_vote_share = p.seen_through_vote_share;
  return s;
}

io::FrameRange frameRange(const LidarSemanticMapParams& p) {
  return io::FrameRange{p.first_frame, p.last_frame, p.stride};
}

}  // namespace mapfuse::stages::detail
