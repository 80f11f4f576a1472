// evaluate's charts show every class on their white paper in a colour of its own (issue 20: lane
// lines were drawn white on white, then lane lines and poles the same grey).
#include <catch2/catch.hpp>
#include <cmath>
#include <opencv2/imgcodecs.hpp>

#include "mapfuse/eval/map_report.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;

namespace {
constexpr double kMinLumaContrast = 100.0;   // 0-255, chart colour against white paper
constexpr double kMinColourDistance = 60.0;  // RGB Euclidean distance between two classes

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

/// The chart `write` draws into a fresh file named `name`, read back (BGR).
template <class Write>
cv::Mat chartOf(const std::string& name, Write write) {
  const std::filesystem::path path = test::tempDir("map_charts_" + name) / name;
  write(path);
  const cv::Mat img = cv::imread(path.string(), cv::IMREAD_COLOR);
  REQUIRE(!img.empty());
  return img;
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
  const cv::Mat img = chartOf("error_per_class.png", [&](const std::filesystem::path& p) {
    eval::writeErrorPerClassPng(p, entry);
  });
  for (int i = 0; i < kNumCrowdClasses; ++i) {
    const auto cls = static_cast<CrowdClass>(i);
    const auto col = crowdClassPaperColor(cls);
    INFO(crowdClassName(cls));
    CHECK(255.0 - luma(col) >= kMinLumaContrast);
    // The filled bar: at least a 10 x 30 px block of the class's chart colour.
    CHECK(pixelsOf(img, col) >= 300);
  }
  // Every class in a colour of its own: lane lines and poles no longer share a grey.
  for (int i = 0; i < kNumCrowdClasses; ++i)
    for (int j = i + 1; j < kNumCrowdClasses; ++j) {
      const auto a = crowdClassPaperColor(static_cast<CrowdClass>(i));
      const auto b = crowdClassPaperColor(static_cast<CrowdClass>(j));
      double d2 = 0;
      for (int k = 0; k < 3; ++k) d2 += (double(a[k]) - b[k]) * (double(a[k]) - b[k]);
      INFO(crowdClassName(static_cast<CrowdClass>(i))
           << " vs " << crowdClassName(static_cast<CrowdClass>(j)));
      CHECK(std::sqrt(d2) >= kMinColourDistance);
    }
  // Colours that read on white stay in the map colour's family: stop lines red.
  const auto stop = crowdClassPaperColor(CrowdClass::kStopLine);
  CHECK(stop[0] > 2 * stop[1]);
  CHECK(stop[0] > 2 * stop[2]);
}

TEST_CASE("error_vs_traversals.png: every class's line and legend in its own colour",
          "[eval][report]") {
  std::vector<eval::MapReportEntry> maps(2);
  for (int m = 0; m < 2; ++m) {
    maps[m].name = "map" + std::to_string(m);
    maps[m].traversals = 5 + 10 * m;
    for (int i = 0; i < kNumCrowdClasses; ++i) {
      eval::ClassMetrics c;
      c.cls = static_cast<CrowdClass>(i);
      c.relative.count = 10;
      c.relative.mean = 0.05 + 0.02 * i - 0.01 * m;
      c.truth_count = 10;
      c.completeness = 0.4 + 0.05 * i + 0.1 * m;
      maps[m].metrics.classes.push_back(c);
    }
  }
  const cv::Mat img = chartOf("error_vs_traversals.png", [&](const std::filesystem::path& p) {
    eval::writeErrorVsTraversalsPng(p, maps);
  });
  for (int i = 0; i < kNumCrowdClasses; ++i) {
    const auto cls = static_cast<CrowdClass>(i);
    INFO(crowdClassName(cls));
    // 4 filled dots of radius 3 (about 29 px each) besides the lines and the legend text.
    CHECK(pixelsOf(img, crowdClassPaperColor(cls)) >= 100);
  }
}
