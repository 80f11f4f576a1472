#pragma once
/// @file Coordinate alignment of Velodyne points with image_02 (Jeong et al. 2018, eq. 2-3):
/// [u v 1]^T ~ P_rect_02 * R_rect_00 * T_cam0_velo * [x y z 1]^T, keeping points whose range
/// lies in [min_range, max_range] and that land inside the image in front of the camera.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "mapfuse/core/param.hpp"
#include "mapfuse/io/kitti_calib.hpp"

namespace mapfuse::lidar {

struct ProjectionSettings {
  double min_range = 5.0;   ///< m, Euclidean distance from the Velodyne origin
  double max_range = 50.0;  ///< m

  template <class V>
  void visit(V& v) {
    v("min_range", min_range, "m", "nearest point used for labelling", param::in(0, 1000));
    v("max_range", max_range, "m", "farthest point used for labelling", param::in(0, 1000));
    v.relation("max_range", max_range, max_range > min_range, "> min_range");
  }
};

/// The camera a scan is projected into: the drive's calibration, not a setting.
struct ImageProjection {
  Eigen::Matrix<double, 3, 4> P = Eigen::Matrix<double, 3, 4>::Zero();  ///< velo -> image_02
  int width = 0;                                                        ///< px
  int height = 0;                                                       ///< px
  /// @brief image_02 of a KITTI calibration: veloToImage2() and S_rect_02.
  static ImageProjection of(const io::KittiCalibration& calib);
};

/// Points of a scan that see the image, with their pixels.
struct ProjectedPoints {
  std::vector<uint32_t> point_index;  ///< index into the scan
  std::vector<int32_t> u, v;          ///< pixel column / row (rounded to the nearest pixel)
  std::size_t size() const { return point_index.size(); }
};

/// @brief Projects one point; returns false when behind the camera (depth <= 0).
/// @param P 3x4 Velodyne -> image matrix (KittiCalibration::veloToImage2())
bool projectPoint(const Eigen::Matrix<double, 3, 4>& P, const Eigen::Vector3d& p_velo, double* u,
                  double* v);

/// @brief eq. (2)-(3): the scan points (velo frame) that land in the image within range.
ProjectedPoints projectScan(const std::vector<Eigen::Vector3f>& points_velo,
                            const ImageProjection& camera, const ProjectionSettings& s);

}  // namespace mapfuse::lidar
