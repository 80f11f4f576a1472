#pragma once
/// @file Incremental semantic labelling of one frame (Jeong et al. 2018, §2.1): coordinate
/// alignment (eq. 2-3), error minimisation (eq. 4 + random forests), and recursive Bayesian
/// fusion (eq. 5-6) into the voxel map. Points of one frame that fall into the same voxel are
/// averaged into one measurement of that voxel for that frame.
#include <Eigen/Core>
#include <vector>

#include "mapfuse/core/se3.hpp"
#include "mapfuse/io/semantic_image.hpp"
#include "mapfuse/lidar/cluster_classifier.hpp"
#include "mapfuse/lidar/clustering.hpp"
#include "mapfuse/lidar/error_minimization.hpp"
#include "mapfuse/lidar/pixel_semantics.hpp"
#include "mapfuse/lidar/projection.hpp"
#include "mapfuse/lidar/voxel_map.hpp"

namespace mapfuse::lidar {

struct FrameFusionSettings {
  ProjectionSettings projection;
  PixelSemanticsSettings pixel;
  ClusteringSettings clustering;
};

struct FrameFusionStats {
  std::size_t points = 0;        ///< scan points
  std::size_t projected = 0;     ///< points in range and inside the image
  std::size_t fused_points = 0;  ///< projected points kept by the error minimisation
  std::size_t fused_voxels = 0;  ///< voxel measurements fused
  std::size_t new_voxels = 0;    ///< voxels created
  ErrorMinimizationStats error_min;
  double t_projection = 0;  ///< s
  double t_error_min = 0;   ///< s (clustering + features + forests)
  double t_fusion = 0;      ///< s
};

/// @brief Labels and fuses one frame into `map`.
/// @param scan_velo the Velodyne points
/// @param T_map_velo pose of the scan in the map
/// @param camera image_02 of the drive's calibration (ImageProjection::of)
/// @param semantics class evidence of image_02 (the camera's image size)
FrameFusionStats fuseFrame(SemanticVoxelMap& map, const std::vector<Eigen::Vector3f>& scan_velo,
                           const Pose3& T_map_velo, const ImageProjection& camera,
                           const io::SemanticImage& semantics, const ClusterClassifier& classifier,
                           const FrameFusionSettings& settings);

/// @brief The projected points of a frame with their argmax pixel labels (training and
/// diagnostics): `points` (velo frame), `labels`, `scan_index`.
struct LabeledProjection {
  std::vector<Eigen::Vector3f> points;
  std::vector<uint8_t> labels;
  std::vector<uint32_t> scan_index;
};
LabeledProjection labelScan(const std::vector<Eigen::Vector3f>& scan_velo,
                            const ImageProjection& camera, const io::SemanticImage& semantics,
                            const ProjectionSettings& s);

}  // namespace mapfuse::lidar
