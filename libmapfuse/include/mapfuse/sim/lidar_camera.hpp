#pragma once
/// @file The camera (image_02) of the synthetic drive: the true per-pixel label image by
/// nearest-hit rendering (one ray per pixel through the same scene as the LiDAR, i.e. an exact
/// z-buffer) with the KITTI P_rect_02 / R_rect_00 / T_cam0_velo, and a shaded colour image.
#include <cstdint>
#include <vector>

#include "mapfuse/core/se3.hpp"
#include "mapfuse/io/kitti_calib.hpp"
#include "mapfuse/sim/lidar_scene.hpp"

namespace mapfuse::sim {

/// What one camera frame sees.
struct CameraFrame {
  int width = 0, height = 0;    ///< px
  std::vector<uint8_t> labels;  ///< width*height LiDAR class ids (0 = nothing / sky)
  std::vector<float> depth;     ///< width*height ray lengths (m), 0 where nothing was hit
};

/// @brief Renders the true label image of camera 2 at pose T_world_velo and time `time`.
/// Pixel (u, v) is the ray through the rectified image point (u, v) (pixel centres at integer
/// coordinates, as rounding a projection to the nearest integer).
/// @param max_range m, farther surfaces count as sky.
CameraFrame renderLabels(const LidarScene& scene, const io::KittiCalibration& calib,
                         const Pose3& T_world_velo, double time, double max_range);

/// @brief A shaded colour picture of a label frame (class palette darkened with distance),
/// 8-bit BGR interleaved, for image_02.
std::vector<uint8_t> shadeLabels(const CameraFrame& frame);

/// @brief Pixel of a Velodyne point in image_02 (eq. 2-3, Jeong et al. 2018); false when
/// behind the camera.
bool projectToImage2(const io::KittiCalibration& calib, const Eigen::Vector3d& p_velo, double& u,
                     double& v);

}  // namespace mapfuse::sim
