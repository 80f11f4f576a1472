// evaluate's charts show every class on their white paper (issue 20: lane lines were drawn white
// on white).
#include <catch2/catch.hpp>
#include <opencv2/imgcodecs.hpp>

#include "mapfuse/eval/map_report.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;

namespace {
constexpr double kMinLumaContrast = 100.0;  // 0-255, chart colour against white paper

double luma(const std::array<uint8_t, 3>& rgb) {
  return 0.299 * rgb[0] + 0.587 * rgb[1] + 0.114 * rgb[2];
}

/// Pixels of exactly the colour `rgb` in a BGR picture.
int pixelsOf(const cv::Mat& bgr, const std::array<uint8_t, 3>& rgb) {
  int n = 0;
  for (int r = 0; r < bgr.rows; ++r)
    for (int c = 0; c < bgr.cols; ++c) {
      const cv::Vec3b p = bgr.at<cv::Vec3b>(r, c);
      n += p[2] == rgb[0] && p[1] == rgb[1] && p[0] == rgb[2];
    }
  return n;
}
}  // namespace

TEST_CASE("error_per_class.png: every class's bar stands out from the white paper",
          "[eval][report]") {
  eval::MapReportEntry entry;
  entry.name = "map.json";
  for (int i = 0; i < kNumCrowdClasses; ++i) {
    eval::ClassMetrics c;
    c.cls = static_cast<CrowdClass>(i);
    c.relative.count = c.absolute.count = 10;
    c.relative.mean = 0.05 + 0.01 * i;
    c.absolute.mean = 0.08 + 0.01 * i;
    entry.metrics.classes.push_back(c);
  }
  const auto dir = test::tempDir("map_charts");
  eval::writeErrorPerClassPng(dir / "error_per_class.png", entry);
  const cv::Mat img = cv::imread((dir / "error_per_class.png").string(), cv::IMREAD_COLOR);
  REQUIRE(!img.empty());
  for (int i = 0; i < kNumCrowdClasses; ++i) {
    const auto cls = static_cast<CrowdClass>(i);
    const auto col = eval::chartColor(cls);
    INFO(crowdClassName(cls));
    CHECK(255.0 - luma(col) >= kMinLumaContrast);
    // The filled bar: at least a 10 x 30 px block of the class's chart colour.
    CHECK(pixelsOf(img, col) >= 300);
  }
  // White lane lines become grey; dark colours stay as in the map.
  CHECK(eval::chartColor(CrowdClass::kLaneLine)[0] == eval::chartColor(CrowdClass::kLaneLine)[2]);
  CHECK(eval::chartColor(CrowdClass::kStopLine) == crowdClassColor(CrowdClass::kStopLine));
}
