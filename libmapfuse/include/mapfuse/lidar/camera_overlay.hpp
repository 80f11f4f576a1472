#pragma once
/// @file Camera overlay pictures (Jeong et al. 2018, Fig. 4): labelled 3D points (the voxels of
/// the finished semantic map, or one scan's points with the map's labels) projected into image_02
/// with the pipeline's eq. (2)-(3), painted far first in the class colours over the camera frame,
/// with a key panel listing the classes drawn (io/picture_key.hpp).
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <filesystem>
#include <opencv2/core.hpp>
#include <set>
#include <string>
#include <vector>

#include "mapfuse/core/classes.hpp"
#include "mapfuse/core/param.hpp"
#include "mapfuse/core/se3.hpp"
#include "mapfuse/io/kitti_raw.hpp"
#include "mapfuse/lidar/voxel_map.hpp"

namespace mapfuse::lidar {

/// Which overlay pictures lidar-semantic-map writes (overlay/<frame>.png).
struct CameraOverlaySettings {
  int every = 0;               ///< every N-th selected frame gets a picture; 0 = none
  std::string source = "map";  ///< "map" (voxels of the finished map) or "scan" (the frame's scan)
  double alpha = 0.6;          ///< opacity of the class colours over the photo (1 = opaque)

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("overlay_every", every, "",
      "write overlay/<frame>.png (labels projected into image_02) for every N-th frame (0 = off)",
      in(0, 100000));
    v("overlay_source", source, "",
      "overlay points: map (voxels of the finished map) or scan (the frame's scan, map labels)",
      oneOf({"map", "scan"}));
    v("overlay_alpha", alpha, "", "opacity of the overlay's class colours over the photo",
      gt(0) & le(1));
  }
};

/// Labelled points to draw, in the Velodyne frame of the picture's frame.
struct OverlayPoints {
  std::vector<Eigen::Vector3f> points_velo;  ///< m
  std::vector<uint8_t> labels;               ///< LidarClass, never unlabeled
};

/// How the points are drawn.
struct OverlayStyle {
  double max_range = 50.0;   ///< m from the Velodyne origin; farther points are left out
  double splat_size = 0.05;  ///< m, footprint of a point (the voxel edge): its square covers
                             ///< splat_size * f_u / depth pixels on a side, clamped to
                             ///< [min_splat_px, max_splat_px]
  int min_splat_px = 1;      ///< px
  int max_splat_px = 9;      ///< px
  double alpha = 0.6;        ///< opacity of the class colours (1 = opaque)
  std::string title;         ///< first line of the key, e.g. the frame id
};

/// One overlay picture and what it shows.
struct CameraOverlay {
  cv::Mat image;   ///< BGR: the photo with the labels, the key panel on its right
  cv::Mat labels;  ///< CV_8UC1, photo size: LidarClass painted at each pixel, 255 = none
  std::set<LidarClass> classes;     ///< classes painted (the legend lists exactly these)
  std::vector<std::string> legend;  ///< the key's legend labels, in order
  std::size_t drawn = 0;            ///< points painted (some may be covered by nearer ones)
  std::size_t behind = 0;           ///< points behind the camera (depth <= 0) or beyond max_range
  std::size_t outside = 0;          ///< points in front whose pixel lies outside the photo
};

/// @brief Paints `pts` into the photo `bgr` (CV_8UC3): each point projected with eq. (2)-(3)
/// ([u v 1]^T ~ P [x y z 1]^T, pixel = round(u), round(v)) as a square of its class colour
/// (lidarClassColor), farthest first so nearer points cover farther ones; the painted pixels are
/// blended with the photo at `style.alpha`; then the key panel (title, legend) is appended.
/// @param P 3x4 Velodyne -> image_02 matrix (KittiCalibration::veloToImage2())
/// @throws InputError when `bgr` is empty or not CV_8UC3, or the sizes of `pts` differ.
CameraOverlay renderCameraOverlay(const cv::Mat& bgr, const OverlayPoints& pts,
                                  const Eigen::Matrix<double, 3, 4>& P, const OverlayStyle& style);

/// @brief The labelled voxel centres of `map` within `max_range` of the Velodyne at `T_map_velo`,
/// in that Velodyne frame (unlabeled voxels left out).
OverlayPoints mapOverlayPoints(const SemanticVoxelMap& map, const Pose3& T_map_velo,
                               double max_range);

/// @brief The scan's points with the label of the map voxel each falls in (points in no voxel or
/// an unlabeled one left out), in the Velodyne frame.
OverlayPoints scanOverlayPoints(const SemanticVoxelMap& map, const Pose3& T_map_velo,
                                const std::vector<Eigen::Vector3f>& points_velo);

/// What writeCameraOverlays wrote.
struct CameraOverlayReport {
  std::vector<std::string> files;                 ///< overlay/<frame>.png written, in frame order
  std::vector<std::string> frames_without_image;  ///< selected frames lacking image_02
  std::size_t points_drawn = 0;                   ///< over all pictures
  std::array<std::size_t, kNumLidarClasses> pictures_with_class{};  ///< per LidarClass
};

/// @brief overlay/<frame>.png for every `settings.every`-th selected frame (positions 0, N, 2N,
/// ... of drive.frames): the finished map's voxels (source "map") or the frame's scan with the
/// map's labels (source "scan") seen from the frame's pose T_map_velo[i]. A frame without
/// image_02 is skipped, named in the report and warned about. No-op when every == 0.
/// @param max_range m, farthest point drawn (the projection's max_range)
/// @throws IoError when a photo cannot be decoded or a picture written; ParseError for a bad scan.
CameraOverlayReport writeCameraOverlays(const io::KittiRawDrive& drive, const SemanticVoxelMap& map,
                                        const std::vector<Pose3>& T_map_velo,
                                        const CameraOverlaySettings& settings, double max_range,
                                        const std::filesystem::path& dir);

}  // namespace mapfuse::lidar
