#pragma once
/// @file The semantic voxel map of one drive (Jeong et al. 2018; docs/lidar.md): poses
/// (lidar/drive_poses.hpp), then frame by frame the image semantics, the projection, the cluster
/// error minimisation and the Bayesian fusion (lidar/frame_fusion.hpp, §2.1), then the batch
/// refinement (lidar/map_refinement.hpp, §2.2).
#include <filesystem>
#include <string>
#include <vector>

#include "mapfuse/core/param.hpp"
#include "mapfuse/io/kitti_raw.hpp"
#include "mapfuse/lidar/drive_poses.hpp"
#include "mapfuse/lidar/frame_fusion.hpp"
#include "mapfuse/lidar/frame_semantics.hpp"
#include "mapfuse/lidar/map_refinement.hpp"
#include "mapfuse/lidar/voxel_map.hpp"

namespace mapfuse::lidar {

struct SemanticMapSettings {
  DrivePoseSettings poses;
  FrameSemanticsSettings semantics;
  FrameFusionSettings fusion;   ///< the projection's image size comes from the drive
  double voxel_size = 0.05;     ///< m
  double min_log_prob = -20.0;  ///< nats, floor of a voxel's class log posterior
  std::string classifier_dir;   ///< rtrees_<label>.yml folder; empty = error minimisation skipped
  MapRefinementSettings refinement;  ///< its free-space test takes the projection's ranges
  int num_threads = 1;               ///< OpenMP threads of the refinement

  template <class V>
  void visit(V& v) {
    using namespace param;
    poses.visit(v);
    semantics.visit(v);
    fusion.pixel.visit(v);
    fusion.projection.visit(v);
    v("voxel_size", voxel_size, "m", "voxel edge", in(0.005, 10));
    v("min_log_prob", min_log_prob, "", "floor of a voxel's class log posterior (nats)",
      ge(-1e6) & lt(0));
    v("classifier_dir", classifier_dir, "",
      "folder of rtrees_<label>.yml (empty = error minimisation skipped)");
    fusion.clustering.visit(v);
    refinement.visit(v);
    v("num_threads", num_threads, "", "OpenMP threads", in(1, 1024));
  }
};

/// Where the frames' semantics came from.
struct SemanticsUse {
  std::string source;                                          ///< "precomputed" or "enet"
  int from_precomputed = 0, from_cache = 0, from_network = 0;  ///< frames
  double network_seconds = 0;                                  ///< s
};

/// Wall times of the steps, s.
struct SemanticMapTimings {
  double open = 0;  ///< forests and segmenter loaded
  double poses = 0, load_scans = 0, semantics = 0, projection = 0, error_minimization = 0,
         fusion = 0;
};

struct SemanticMapResult {
  SemanticVoxelMap map;  ///< refined, memory shrunk
  DrivePoses poses;
  SemanticsUse semantics;
  std::vector<std::string> forest_labels;  ///< labels with a forest
  std::string error_min_skipped;  ///< why the error minimisation did not run; empty = it ran
  ErrorMinimizationStats error_min;
  std::size_t points_projected = 0, points_fused = 0;
  std::size_t voxels_after_fusion = 0;       ///< before refinement
  double bytes_per_voxel = 0;                ///< B, after refinement
  double bytes_per_voxel_before_shrink = 0;  ///< B, after fusion
  MapRefinementResult refinement;
  SemanticMapTimings timings;
};

/// @brief `fusion` with the projection's image size taken from the drive's calibration.
FrameFusionSettings fusionForDrive(FrameFusionSettings fusion, const io::KittiRawDrive& drive);

/// @brief Builds the semantic voxel map of the selected frames of `drive`.
/// @param semantics_cache where ENet outputs are cached (settings.semantics.cache)
/// @throws InputError / IoError / ParseError from the inputs, the poses and the forests.
SemanticMapResult buildSemanticMap(const io::KittiRawDrive& drive,
                                   const SemanticMapSettings& settings,
                                   const std::filesystem::path& semantics_cache);

}  // namespace mapfuse::lidar
