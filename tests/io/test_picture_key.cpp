// The key of top-down pictures (issue 20): a legend with every class drawn, a scale bar of a
// round length, a north arrow, in a panel beside the picture.
#include <catch2/catch.hpp>

#include "mapfuse/io/picture_key.hpp"
#include "support/picture_pixels.hpp"

using namespace mapfuse;
using test::pixelsOf;

TEST_CASE("Picture key: the scale bar is the longest 1-2-5 length that fits", "[io][picture]") {
  CHECK(io::scaleBarLength(0.1, 170) == Approx(10.0));  // 17 m fit
  CHECK(io::scaleBarLength(0.05, 170) == Approx(5.0));  // 8.5 m
  CHECK(io::scaleBarLength(0.2, 170) == Approx(20.0));  // 34 m
  CHECK(io::scaleBarLength(0.3, 170) == Approx(50.0));  // 51 m
  CHECK(io::scaleBarLength(2.0, 170) == Approx(200.0));
}

TEST_CASE("Picture key: every class present has a legend swatch beside the untouched picture",
          "[io][picture]") {
  const std::set<CrowdClass> present = {CrowdClass::kLaneLine, CrowdClass::kStopLine,
                                        CrowdClass::kTrafficLight};
  io::PictureKey key;
  key.legend = io::crowdLegend(present);
  REQUIRE(key.legend.size() == present.size());
  std::size_t k = 0;
  for (CrowdClass c : present) CHECK(key.legend[k++].label == crowdClassName(c));
  key.legend.push_back({"trajectory", {0, 160, 255}, true});
  key.metres_per_pixel = 0.1;
  const cv::Mat picture(100, 300, CV_8UC3, cv::Scalar(40, 40, 40));
  const cv::Mat out = io::withPictureKey(picture, key);
  CHECK(out.cols == 500);
  CHECK(out.rows >= 100);
  // The picture is copied unchanged.
  CHECK(cv::norm(out(cv::Rect(0, 0, 300, 100)), picture, cv::NORM_INF) == 0.0);
  // Each legend entry's colour appears in the panel (swatch 12 x 12 inside its border).
  const cv::Rect panel(300, 0, 200, out.rows);
  for (const auto& e : key.legend) {
    INFO(e.label);
    CHECK(pixelsOf(out, panel, e.rgb) >= (e.line ? 10 : 144));
  }
  // The scale bar: 10 m at 0.1 m/px is 100 px of black in one row.
  int longest = 0;
  for (int r = 0; r < out.rows; ++r) {
    int run = 0;
    for (int c = 300; c < out.cols; ++c) {
      const cv::Vec3b p = out.at<cv::Vec3b>(r, c);
      run = (p[0] == 0 && p[1] == 0 && p[2] == 0) ? run + 1 : 0;
      longest = std::max(longest, run);
    }
  }
  CHECK(longest >= 100);
  CHECK(longest <= 102);
}

TEST_CASE("Picture key: lidar legend in SemanticKITTI colours", "[io][picture]") {
  const auto legend = io::lidarLegend({LidarClass::kRoad, LidarClass::kVehicle});
  REQUIRE(legend.size() == 2);
  CHECK(legend[0].label == "road");
  CHECK(legend[1].label == "vehicle");
  CHECK(legend[1].rgb == lidarClassColor(LidarClass::kVehicle));
}

TEST_CASE("Picture key: drawPath counts the path points inside the picture", "[io][picture]") {
  cv::Mat img(100, 100, CV_8UC3, cv::Scalar(255, 255, 255));
  // Top-left corner at map (0, 10), 0.1 m/px: (1, 9) is pixel (10, 10); (50, 5) lies outside.
  CHECK(io::drawPath(img, {{1, 9, 0}, {5, 5, 0}, {50, 5, 0}}, {0, 10}, 0.1, {230, 0, 0}) == 2);
  const cv::Vec3b p = img.at<cv::Vec3b>(10, 10);
  CHECK((p[2] > 200 && p[0] < 60));
}
