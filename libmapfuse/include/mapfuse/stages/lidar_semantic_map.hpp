#pragma once
/// @file Stage `lidar-semantic-map` (Jeong et al. 2018; docs/lidar.md): KITTI raw drive ->
/// semantic voxel map (PLY, PCD), per-scan SemanticKITTI labels, top-down PNG, poses, summary
/// (lidar::buildSemanticMap); and `train`, which fits the per-label cluster classifiers from
/// labelled drives (lidar::trainClusterClassifier).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "mapfuse/io/kitti_raw.hpp"
#include "mapfuse/lidar/classifier_training.hpp"
#include "mapfuse/lidar/cluster_classifier.hpp"
#include "mapfuse/lidar/map_export.hpp"
#include "mapfuse/lidar/semantic_mapper.hpp"

namespace mapfuse::stages {

struct LidarSemanticMapParams {
  static constexpr const char* kName = "LidarSemanticMapParams";
  io::FrameRange frames;
  lidar::SemanticMapSettings map;
  lidar::RTreesSettings rtrees;  ///< train only
  lidar::MapExportSettings exports;

  template <class V>
  void visit(V& v) {
    frames.visit(v);
    map.visit(v);
    rtrees.visit(v);
    exports.visit(v);
  }
};

/// @brief The map's part of lidar-semantic-map.summary.json: poses (with the odometry report
/// when odometry ran), semantics, error minimisation, counts, memory, refinement, timings.
nlohmann::json toJson(const lidar::SemanticMapResult& r,
                      const lidar::DriveOdometrySettings& odometry);

/// @brief lidar-semantic-map-train.summary.json: per drive, per label and the forests.
nlohmann::json toJson(const lidar::ClassifierTrainingResult& r);

/// @brief Builds the semantic voxel map of one drive into `output` (map.ply, map.pcd,
/// labels/<frame>.label, topdown.png, poses.txt, poses_velo.txt,
/// lidar-semantic-map.{config,summary}.json); a failed run leaves the folder as it was.
lidar::SemanticMapResult runLidarSemanticMap(const std::filesystem::path& drive,
                                             const std::filesystem::path& output,
                                             const LidarSemanticMapParams& params);

/// @brief Fits the per-label RTrees from drives that carry labels/<frame>.label files, chooses
/// each label's threshold on the `validation` drives (none: majority vote, every forest kept);
/// writes rtrees_<label>.yml, thresholds.json and lidar-semantic-map-train.{config,summary}.json
/// into `output`.
lidar::ClassifierTrainingResult runLidarSemanticMapTrain(
    const std::vector<std::filesystem::path>& drives,
    const std::vector<std::filesystem::path>& validation, const std::filesystem::path& output,
    const LidarSemanticMapParams& params);

}  // namespace mapfuse::stages
