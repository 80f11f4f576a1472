#pragma once
/// @file Top-down (bird's-eye) picture of an LSM in its own frame: trajectory, keyframes and
/// elements in class colours, optionally over a mosaic of per-frame BEV images.
#include <opencv2/core.hpp>
#include <vector>

#include "mapfuse/core/lsm.hpp"
#include "mapfuse/io/picture_key.hpp"
#include "mapfuse/vehicle/camera.hpp"

namespace mapfuse::vehicle {

/// A BEV image of one frame placed on the ground (see LaneDetection::bev_gray).
struct BevTile {
  cv::Mat gray;       ///< row 0 = max_x (far), col 0 = +half_width (left)
  Pose3 T_odom_cam;   ///< camera pose of the frame
  GroundPlane plane;  ///< plane the BEV was computed on (camera frame)
  double min_x = 0.0, max_x = 0.0, half_width = 0.0, resolution = 0.05;  ///< m
};

/// @brief Renders the LSM (x east/right, y up in the picture) at `resolution` m/px.
/// @param tiles optional background BEV images (grey), drawn first.
cv::Mat renderTopDown(const Lsm& lsm, const std::vector<Pose3>& trajectory, double resolution,
                      const std::vector<BevTile>& tiles = {});

/// @brief The key of renderTopDown's picture (io/picture_key.hpp): one legend line per class
/// present in `lsm`, the trajectory and the keyframes, a scale bar at `resolution` m/px, +y up;
/// a north arrow only for an LSM in ENU (an odometry-frame LSM gets a note instead).
io::PictureKey topDownKey(const Lsm& lsm, double resolution);

}  // namespace mapfuse::vehicle
