// lidar-semantic-map's topdown.png (issue 35): pole voxels, pale yellow (255, 240, 150) on white
// paper, are ringed in dark grey so they read; the north arrow is drawn only where north is
// known (OXTS poses), otherwise the key says what points up.
#include <algorithm>
#include <catch2/catch.hpp>

#include "mapfuse/core/classes.hpp"
#include "mapfuse/lidar/map_export.hpp"
#include "mapfuse/lidar/voxel_map.hpp"

using namespace mapfuse;

namespace {
constexpr double kRes = 0.1;  // m per pixel
lidar::SemanticVoxelMap mapWith(const std::vector<std::pair<Eigen::Vector3d, LidarClass>>& v) {
  lidar::SemanticVoxelMap map(0.1);
  for (const auto& [p, c] : v) {
    lidar::ClassDistribution d{};
    d.fill(0.01f);
    d[static_cast<int>(c)] = 0.93f;
    map.fuse(map.findOrInsert(lidar::packKey(map.coordOf(p))), d);
  }
  return map;
}
bool isRgb(const cv::Vec3b& p, const std::array<uint8_t, 3>& rgb) {
  return p[2] == rgb[0] && p[1] == rgb[1] && p[0] == rgb[2];
}
}  // namespace

TEST_CASE("LiDAR top-down: poles are ringed in dark grey, readable on white", "[lidar][picture]") {
  // One pole voxel in a 5 x 5 m patch of road.
  std::vector<std::pair<Eigen::Vector3d, LidarClass>> voxels;
  for (double x = 0; x < 5; x += 0.5) voxels.push_back({{x, 0, 0}, LidarClass::kRoad});
  voxels.push_back({{2.5, 4, 1}, LidarClass::kPole});
  const auto map = mapWith(voxels);
  const auto pic = lidar::renderTopDownPicture(map, {Pose3::Identity()}, kRes, true);
  const cv::Mat img = pic.image(cv::Rect(0, 0, pic.width, pic.height));
  const auto pole = lidarClassColor(LidarClass::kPole);
  int pole_px = 0, dark_px = 0;
  for (int r = 0; r < img.rows; ++r)
    for (int c = 0; c < img.cols; ++c) {
      const cv::Vec3b p = img.at<cv::Vec3b>(r, c);
      pole_px += isRgb(p, pole);
      dark_px += isRgb(p, {70, 70, 70});
    }
  CHECK(pole_px >= 9);                       // a dot of radius 2 px, not one pixel
  CHECK(dark_px >= 8);                       // its ring
  CHECK(pic.image.cols == pic.width + 200);  // the key beside it
}

TEST_CASE("LiDAR top-down: a north arrow only when north is known", "[lidar][picture]") {
  const auto map = mapWith({{{0, 0, 0}, LidarClass::kRoad}, {{3, 2, 0}, LidarClass::kRoad}});
  const auto north = lidar::renderTopDownPicture(map, {Pose3::Identity()}, kRes, true);
  const auto none = lidar::renderTopDownPicture(map, {Pose3::Identity()}, kRes, false);
  // The arrow's 2 px shaft below its head: a column of black pixels 20 px long in the panel.
  auto longestBlackColumn = [](const cv::Mat& img, int from) {
    int best = 0;
    for (int c = from; c < img.cols; ++c)
      for (int r = 0, run = 0; r < img.rows; ++r) {
        const cv::Vec3b p = img.at<cv::Vec3b>(r, c);
        run = (p[0] == 0 && p[1] == 0 && p[2] == 0) ? run + 1 : 0;
        best = std::max(best, run);
      }
    return best;
  };
  CHECK(longestBlackColumn(north.image, north.width + 1) >= 30);  // head + shaft
  CHECK(longestBlackColumn(none.image, none.width + 1) < 15);     // text only
}
