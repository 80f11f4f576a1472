#include "mapfuse/lidar/map_export.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <set>

#include "mapfuse/core/classes.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/io/picture_key.hpp"

namespace mapfuse::lidar {

LabeledCloud toLabeledCloud(const SemanticVoxelMap& map) {
  LabeledCloud c;
  c.points.reserve(map.size());
  c.labels.reserve(map.size());
  c.confidence.reserve(map.size());
  for (std::size_t i = 0; i < map.size(); ++i) {
    const Voxel& v = map.voxels()[i];
    c.points.push_back(map.center(v.key).cast<float>());
    c.labels.push_back(v.label);
    c.confidence.push_back(map.confidence(i));
  }
  return c;
}

std::vector<uint32_t> scanLabels(const SemanticVoxelMap& map, const Pose3& T_map_velo,
                                 const std::vector<Eigen::Vector3f>& points_velo,
                                 const RemovedVoxelLabels* removed) {
  constexpr uint32_t kMovingCar = 252;  // SemanticKITTI
  std::vector<uint32_t> out(points_velo.size(), 0);
  for (std::size_t i = 0; i < points_velo.size(); ++i) {
    const Eigen::Vector3d p = T_map_velo * points_velo[i].cast<double>();
    const VoxelCoord c = map.coordOf(p);
    constexpr int32_t kLim = (1 << 20) - 1;
    if (std::abs(c.x) > kLim || std::abs(c.y) > kLim || std::abs(c.z) > kLim) continue;
    const uint64_t key = packKey(c);
    const int64_t j = map.find(key);
    if (j >= 0) {
      out[i] = semanticKittiId(static_cast<LidarClass>(map.voxels()[j].label));
    } else if (removed) {
      const auto it = removed->find(key);
      if (it == removed->end()) continue;
      const auto cls = static_cast<LidarClass>(it->second.label);
      out[i] = cls == LidarClass::kVehicle && it->second.trace ? kMovingCar : semanticKittiId(cls);
    }
  }
  return out;
}

cv::Mat renderTopDown(const SemanticVoxelMap& map, double resolution, Eigen::Vector2d* origin_xy) {
  if (!(resolution > 0)) throw InputError("top-down resolution must be > 0");
  if (map.empty()) {
    if (origin_xy) origin_xy->setZero();
    return cv::Mat(1, 1, CV_8UC3, cv::Scalar(255, 255, 255));
  }
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (const Voxel& v : map.voxels()) {
    const Eigen::Vector3d c = map.center(v.key);
    lo = lo.cwiseMin(c.head<2>());
    hi = hi.cwiseMax(c.head<2>());
  }
  constexpr int kMaxSide = 8000;
  const int w = static_cast<int>(std::ceil((hi.x() - lo.x()) / resolution)) + 1;
  const int h = static_cast<int>(std::ceil((hi.y() - lo.y()) / resolution)) + 1;
  if (w > kMaxSide || h > kMaxSide)
    throw InputError("top-down image would be " + std::to_string(w) + "x" + std::to_string(h) +
                     " px; increase the resolution (m per pixel)");
  cv::Mat img(h, w, CV_8UC3, cv::Scalar(255, 255, 255));
  cv::Mat top(h, w, CV_32F, cv::Scalar(-std::numeric_limits<float>::infinity()));
  for (const Voxel& v : map.voxels()) {
    const Eigen::Vector3d c = map.center(v.key);
    const int u = static_cast<int>((c.x() - lo.x()) / resolution);
    const int r = h - 1 - static_cast<int>((c.y() - lo.y()) / resolution);
    float& z = top.at<float>(r, u);
    if (c.z() <= z) continue;
    z = static_cast<float>(c.z());
    const auto col = lidarClassColor(static_cast<LidarClass>(v.label));
    img.at<cv::Vec3b>(r, u) = cv::Vec3b(col[2], col[1], col[0]);
  }
  if (origin_xy) *origin_xy = Eigen::Vector2d(lo.x(), hi.y() + resolution);
  return img;
}

namespace {
/// Poles are a few pixels of pale yellow (255, 240, 150), hardly visible on white paper: each pole
/// pixel becomes a dot of radius 2 px in its colour with a dark grey ring around it.
void markPoles(cv::Mat& img) {
  const auto c = lidarClassColor(LidarClass::kPole);
  const cv::Vec3b pole(c[2], c[1], c[0]);
  std::vector<cv::Point> at;
  for (int r = 0; r < img.rows; ++r)
    for (int u = 0; u < img.cols; ++u)
      if (img.at<cv::Vec3b>(r, u) == pole) at.emplace_back(u, r);
  for (const auto& p : at) cv::circle(img, p, 3, cv::Scalar(70, 70, 70), cv::FILLED, cv::LINE_8);
  for (const auto& p : at) cv::circle(img, p, 2, cv::Scalar(pole), cv::FILLED, cv::LINE_8);
}
}  // namespace

TopDownPicture renderTopDownPicture(const SemanticVoxelMap& map,
                                    const std::vector<Pose3>& T_map_velo, double resolution,
                                    bool north_up) {
  TopDownPicture out;
  cv::Mat img = renderTopDown(map, resolution, &out.origin_xy);
  markPoles(img);
  out.width = img.cols;
  out.height = img.rows;
  const std::array<uint8_t, 3> path_rgb{230, 0, 0};
  std::vector<Eigen::Vector3d> path;
  for (const Pose3& T : T_map_velo) path.push_back(T.translation());
  const int path_shown = io::drawPath(img, path, out.origin_xy, resolution, path_rgb);
  std::set<LidarClass> present;
  for (const auto& v : map.voxels()) present.insert(static_cast<LidarClass>(v.label));
  io::PictureKey key{io::lidarLegend(present), resolution, north_up, "LiDAR map, top down",
                     "no north (no GPS): up is the car's left at the first frame"};
  if (path_shown > 0) key.legend.push_back({"trajectory", path_rgb, true});
  out.image = io::withPictureKey(img, key);
  return out;
}

}  // namespace mapfuse::lidar
