// ENet through OpenCV DNN on a real KITTI frame.
#include <catch2/catch.hpp>
#include <opencv2/imgcodecs.hpp>

#include "mapfuse/core/classes.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/lidar/enet_segmenter.hpp"
#include "mapfuse/lidar/pixel_semantics.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;

namespace {
// Fraction of a region's pixels that must carry the expected class.
constexpr double kMinRegionAgreement = 0.6;
constexpr int kProbSumTolerance = 8;  // quantisation of 8 channels to 1/255 each

double fractionOf(const io::SemanticImage& img, const cv::Rect& r, LidarClass c) {
  int hit = 0;
  for (int v = r.y; v < r.y + r.height; ++v)
    for (int u = r.x; u < r.x + r.width; ++u) hit += lidar::pixelLabel(img, u, v) == uint8_t(c);
  return static_cast<double>(hit) / r.area();
}
}  // namespace

TEST_CASE("ENet labels the road and the car ahead on sfnd frame 10", "[lidar][enet]") {
  const auto model = test::requireShared("models/enet-cityscapes/enet-model.net");
  const auto image = test::requireShared(
      "data/kitti_raw/2011_09_26/2011_09_26_drive_sfnd_sync/image_02/data/0000000010.png");
  lidar::EnetSegmenter enet(model, {});
  const cv::Mat bgr = cv::imread(image.string(), cv::IMREAD_COLOR);
  const auto sem = enet.segment(bgr);
  REQUIRE(sem.width == bgr.cols);
  REQUIRE(sem.height == bgr.rows);
  REQUIRE(sem.channels == kNumLidarClasses);
  for (int v = 0; v < sem.height; v += 37)
    for (int u = 0; u < sem.width; u += 53) {
      int sum = 0;
      for (int c = 0; c < 8; ++c) sum += sem.prob(u, v)[c];
      CHECK(std::abs(sum - 255) <= kProbSumTolerance);
    }
  if (const char* dump = std::getenv("MAPFUSE_DUMP_ENET")) {
    cv::Mat vis(sem.height, sem.width, CV_8UC3);
    for (int v = 0; v < sem.height; ++v)
      for (int u = 0; u < sem.width; ++u) {
        const auto col = lidarClassColor(static_cast<LidarClass>(lidar::pixelLabel(sem, u, v)));
        vis.at<cv::Vec3b>(v, u) = cv::Vec3b(col[2], col[1], col[0]);
      }
    cv::imwrite(dump, vis);
  }
  // Regions read off the image by eye: the lane left of the car ahead is road, the silver
  // car ahead (x 560-700, y 200-310) is a vehicle.
  const double road = fractionOf(sem, cv::Rect(400, 330, 120, 40), LidarClass::kRoad);
  const double car = fractionOf(sem, cv::Rect(575, 210, 110, 90), LidarClass::kVehicle);
  INFO("road fraction " << road << ", car fraction " << car);
  CHECK(road > kMinRegionAgreement);
  CHECK(car > kMinRegionAgreement);
}

TEST_CASE("ENet: a missing model is an IoError", "[lidar][enet]") {
  CHECK_THROWS_AS(lidar::EnetSegmenter("/nonexistent/enet.net", {}), IoError);
}
