#pragma once
/// @file Views of the semantic voxel map: the labelled cloud of voxel centres (PLY / PCD),
/// per-scan SemanticKITTI labels, and the top-down picture.
#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core.hpp>
#include <unordered_map>
#include <vector>

#include "mapfuse/core/labeled_cloud.hpp"
#include "mapfuse/core/param.hpp"
#include "mapfuse/core/se3.hpp"
#include "mapfuse/lidar/camera_overlay.hpp"
#include "mapfuse/lidar/voxel_map.hpp"

namespace mapfuse::lidar {

/// The views lidar-semantic-map writes besides the map.
struct MapExportSettings {
  double topdown_resolution = 0.1;  ///< m/px
  bool write_scan_labels = true;    ///< labels/<frame>.label for every input scan
  CameraOverlaySettings overlay;    ///< overlay/<frame>.png pictures (off by default)

  template <class V>
  void visit(V& v) {
    v("topdown_resolution", topdown_resolution, "m", "top-down PNG pixel size",
      param::in(0.001, 100));
    v("write_scan_labels", write_scan_labels, "",
      "write labels/<frame>.label for every input scan");
    overlay.visit(v);
  }
};

/// @brief Voxel centres with their argmax label and its posterior probability.
LabeledCloud toLabeledCloud(const SemanticVoxelMap& map);

/// A voxel refinement took out of the map: its label, and whether it went as a moving object's
/// trace (rather than as an isolated voxel).
struct RemovedVoxel {
  uint8_t label = 0;  ///< LidarClass
  bool trace = false;
};
/// The voxels refinement removed, by voxel key.
using RemovedVoxelLabels = std::unordered_map<uint64_t, RemovedVoxel>;

/// @brief SemanticKITTI label word per scan point: the semantic id of the label of the voxel the
/// point falls in (T_map_velo applied), 0 (unlabeled) where the map has no voxel. With `removed`,
/// a point in a voxel refinement removed keeps that voxel's label — the map is cleaned, the
/// point's fused label is still the best guess — vehicles of traces as SemanticKITTI's moving-car
/// (252): the static map leaves them out, the scan still shows them.
std::vector<uint32_t> scanLabels(const SemanticVoxelMap& map, const Pose3& T_map_velo,
                                 const std::vector<Eigen::Vector3f>& points_velo,
                                 const RemovedVoxelLabels* removed = nullptr);

/// @brief Top-down picture (BGR, north/+y up): each pixel shows the class colour of the highest
/// voxel in its column; `resolution` m per pixel; white where the map is empty.
/// @param[out] origin_xy map (x, y) of the top-left pixel corner, m
cv::Mat renderTopDown(const SemanticVoxelMap& map, double resolution, Eigen::Vector2d* origin_xy);

/// The top-down picture with its key (classes drawn, trajectory, scale bar, north arrow).
struct TopDownPicture {
  cv::Mat image;              ///< BGR, with the key (io/picture_key.hpp)
  Eigen::Vector2d origin_xy;  ///< m, map (x, y) of the top-left corner of the map part
  int width = 0, height = 0;  ///< px, the map part
};

/// @brief renderTopDown with pole pixels enlarged and ringed in dark grey (readable on white), the
/// trajectory of `T_map_velo` drawn in red and the picture key: a north arrow when `north_up`
/// (OXTS poses: +y is north), else a note that up is the car's left at the first frame (the
/// Velodyne frame of odometry and poses files: x forward, y left).
TopDownPicture renderTopDownPicture(const SemanticVoxelMap& map,
                                    const std::vector<Pose3>& T_map_velo, double resolution,
                                    bool north_up);

}  // namespace mapfuse::lidar
