// map.png / map_over_truth.png (issue 35): every class drawn keeps pixels of its own colour (a
// sign and a light at the foot of a pole too), the key lists each class drawn and the grey
// background under its given name, and the title is not cut.
#include <algorithm>
#include <catch2/catch.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <set>

#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/map_png.hpp"
#include "mapfuse/io/picture_key.hpp"
#include "mapfuse/io/png_decode.hpp"
#include "support/picture_pixels.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;
using test::pixelsOf;

namespace {
MapInstance instance(CrowdClass c, std::vector<Eigen::Vector3d> pts) {
  MapInstance m;
  m.cls = c;
  m.points = std::move(pts);
  return m;
}
}  // namespace

TEST_CASE("map.png: a sign and a light on their pole stay visible, the key lists every class",
          "[io][picture]") {
  VectorMap map;
  map.instances.push_back(instance(CrowdClass::kLaneLine, {{0, 0, 0}, {40, 0, 0}}));
  map.instances.push_back(
      instance(CrowdClass::kCrosswalk, {{10, 3, 0}, {14, 3, 0}, {14, 8, 0}, {10, 8, 0}}));
  // A sign (0.6 m wide plate) and a light, each at its pole (the pole listed last, as
  // aggregate's output order may put it).
  map.instances.push_back(
      instance(CrowdClass::kTrafficSign, {{20, 5, 2}, {20.6, 5, 2}, {20.6, 5, 2.6}, {20, 5, 2.6}}));
  map.instances.push_back(instance(CrowdClass::kTrafficLight, {{30, 5, 0}}));
  map.instances.push_back(instance(CrowdClass::kPole, {{20.3, 5, 0}}));
  map.instances.push_back(instance(CrowdClass::kPole, {{30, 5, 0}}));
  const std::vector<std::vector<Eigen::Vector3d>> truth = {{{0, -1, 0}, {40, -1, 0}}};
  const auto dir = test::tempDir("map_png");
  io::MapPngOptions opt;
  opt.title = "map (colours) over the truth (grey), a title longer than the panel";
  opt.background_label = "truth";
  io::writeMapPng(dir / "m.png", map, truth, opt);
  const cv::Mat img = io::decodePng(io::readBytes(dir / "m.png"), "m.png", cv::IMREAD_COLOR);
  REQUIRE(img.type() == CV_8UC3);
  const int map_cols = img.cols - 200;  // the key panel is 200 px wide
  REQUIRE(map_cols > 16);
  const cv::Rect picture(0, 0, map_cols, img.rows), panel(map_cols, 0, 200, img.rows);
  for (CrowdClass c : {CrowdClass::kLaneLine, CrowdClass::kCrosswalk, CrowdClass::kTrafficSign,
                       CrowdClass::kTrafficLight, CrowdClass::kPole}) {
    INFO(crowdClassName(c));
    CHECK(pixelsOf(img, picture, crowdClassPaperColor(c)) > 0);   // drawn, not hidden
    CHECK(pixelsOf(img, panel, crowdClassPaperColor(c)) >= 100);  // its 14 x 14 swatch
  }
  // No class not drawn has a swatch; the truth's grey has its (line) entry.
  CHECK(pixelsOf(img, panel, crowdClassPaperColor(CrowdClass::kStopLine)) == 0);
  CHECK(pixelsOf(img, panel, {190, 190, 190}) > 0);
  // The title wraps onto lines that fit the panel: no ink touches its right edge.
  int edge_ink = 0;
  for (int r = 0; r < 60; ++r) edge_ink += img.at<cv::Vec3b>(r, img.cols - 1)[0] < 128;
  CHECK(edge_ink == 0);
}

TEST_CASE("Picture key: titles wrap to the panel at spaces and underscores", "[io][picture]") {
  const std::string title = "2011_09_26_drive_0001_sync (KITTI sfnd) bird's-eye view";
  const auto lines = io::wrapText(title, 0.48, 180);
  REQUIRE(lines.size() >= 2);
  std::string joined;
  for (const auto& l : lines) {
    int baseline = 0;
    CHECK(cv::getTextSize(l, cv::FONT_HERSHEY_SIMPLEX, 0.48, 1, &baseline).width <= 180);
    joined += l;
  }
  // Nothing lost but the spaces at the line breaks.
  std::string a = title, b = joined;
  a.erase(std::remove(a.begin(), a.end(), ' '), a.end());
  b.erase(std::remove(b.begin(), b.end(), ' '), b.end());
  CHECK(a == b);
  CHECK(io::wrapText("short", 0.48, 180) == std::vector<std::string>{"short"});
  CHECK(io::wrapText("", 0.48, 180).empty());
}
