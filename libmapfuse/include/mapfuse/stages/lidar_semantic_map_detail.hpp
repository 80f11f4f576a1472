#pragma once
/// @file Internals shared by the lidar-semantic-map and train stage functions: settings built
/// from the Params, and the semantics source of a drive.
#include <filesystem>

#include "mapfuse/io/kitti_raw.hpp"
#include "mapfuse/lidar/cluster_classifier.hpp"
#include "mapfuse/lidar/frame_fusion.hpp"
#include "mapfuse/lidar/frame_semantics.hpp"
#include "mapfuse/lidar/refinement.hpp"
#include "mapfuse/lidar/seen_through_filter.hpp"
#include "mapfuse/stages/lidar_semantic_map.hpp"

namespace mapfuse::stages::detail {

/// @brief Projection / pixel / clustering settings of a drive.
lidar::FrameFusionSettings fusionSettings(const LidarSemanticMapParams& p,
                                          const io::KittiRawDrive& drive);

/// @brief Semantics source settings; `cache_dir` empty = no ENet cache.
lidar::FrameSemanticsSettings semanticsSettings(const LidarSemanticMapParams& p,
                                                const std::filesystem::path& cache_dir);

/// @brief RTrees training settings.
lidar::RTreesSettings rtreesSettings(const LidarSemanticMapParams& p);

/// @brief Batch refinement settings (K-nearest filter, vehicle-trace removal).
lidar::KnnFilterSettings knnSettings(const LidarSemanticMapParams& p);
lidar::VehicleTraceSettings traceSettings(const LidarSemanticMapParams& p);
lidar::SeenThroughSettings seenThroughSettings(const LidarSemanticMapParams& p);

/// @brief Frame selection.
io::FrameRange frameRange(const LidarSemanticMapParams& p);

}  // namespace mapfuse::stages::detail
