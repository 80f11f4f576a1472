// Issue 21: colour/shape cues for aerial elements (a prohibition sign's red ring, a lit signal
// lamp in its dark housing) above the horizon, and what they must not take: a red panel, a
// red disc, a lamp below the horizon (a tail light), a lamp on a bright background.
#include <catch2/catch.hpp>
#include <opencv2/imgproc.hpp>

#include "mapfuse/vehicle/aerial_colour.hpp"

using namespace mapfuse;
using namespace mapfuse::vehicle;

namespace {
constexpr double kCentreTol = 1.0;  // px: the ring's centre from its width, the lamp's centroid

// KITTI-like camera looking level: the horizon is row cy = 173.
Eigen::Matrix3d kittiK() {
  Eigen::Matrix3d K;
  K << 721.5, 0, 609.6, 0, 721.5, 172.9, 0, 0, 1;
  return K;
}
const Eigen::Vector3d kNormalCam(0, -1, 0);  // ground normal (up) in the camera frame (y down)

const cv::Scalar kRed(30, 30, 220), kWhite(235, 235, 235), kSky(240, 220, 200);
}  // namespace

TEST_CASE("colour cues: the horizon row of a level camera is cy", "[vehicle][aerial][colour]") {
  CHECK(horizonRow(100, kittiK(), kNormalCam) == Approx(172.9));
  // Camera pitched down by 0.02 rad: the horizon moves up by fy * tan(0.02) = 14.4 px.
  const Eigen::Vector3d tilted(0, -std::cos(0.02), -std::sin(0.02));
  CHECK(horizonRow(609.6, kittiK(), tilted) == Approx(172.9 - 721.5 * std::tan(0.02)).margin(1e-6));
}

TEST_CASE("colour cues: a red ring and a lit lamp above the horizon, clutter rejected",
          "[vehicle][aerial][colour]") {
  cv::Mat img(375, 1242, CV_8UC3, kSky);
  // Sign: white disc with a red ring, diameter 30 px, centre (200, 80); its lower 30 % hidden
  // behind a dark truck roof (as sign A of the sfnd drive from frame ~25).
  cv::circle(img, {200, 80}, 15, kWhite, cv::FILLED);
  cv::circle(img, {200, 80}, 13, kRed, 3);
  cv::rectangle(img, cv::Rect(150, 90, 120, 40), cv::Scalar(40, 30, 30), cv::FILLED);
  // Lamp: dark housing 24x40 at (594, 94), lit red lamp radius 3 at (606, 106).
  cv::rectangle(img, cv::Rect(594, 94, 24, 40), cv::Scalar(20, 20, 20), cv::FILLED);
  cv::circle(img, {606, 106}, 3, kRed, cv::FILLED);
  // Clutter: a red panel (truck tarp), a red disc, a red lamp on the bright sky, and a lit red
  // lamp in a dark housing below the horizon (a tail light).
  cv::rectangle(img, cv::Rect(800, 40, 60, 40), kRed, cv::FILLED);
  cv::circle(img, {950, 60}, 14, kRed, cv::FILLED);
  cv::circle(img, {1050, 60}, 3, kRed, cv::FILLED);
  cv::rectangle(img, cv::Rect(400, 200, 30, 20), cv::Scalar(20, 20, 20), cv::FILLED);
  cv::circle(img, {412, 210}, 3, kRed, cv::FILLED);

  const auto det = detectColourCues(img, kittiK(), kNormalCam, ColourCueSettings{});
  REQUIRE(det.size() == 2);
  const auto& sign = det[0].cls == CrowdClass::kTrafficSign ? det[0] : det[1];
  const auto& lamp = det[0].cls == CrowdClass::kTrafficLight ? det[0] : det[1];
  REQUIRE(sign.cls == CrowdClass::kTrafficSign);
  REQUIRE(lamp.cls == CrowdClass::kTrafficLight);
  REQUIRE(sign.points.size() == 1);
  CHECK((sign.points[0] - Eigen::Vector2d(200, 80)).norm() < kCentreTol);
  CHECK((lamp.points[0] - Eigen::Vector2d(606, 106)).norm() < kCentreTol);
  CHECK(sign.detector == 1);
  CHECK(lamp.detector == 1);

  ColourCueSettings off;
  off.enabled = false;
  CHECK(detectColourCues(img, kittiK(), kNormalCam, off).empty());
  // The sign more than 40 % hidden is not taken (its centre would be a guess).
  cv::rectangle(img, cv::Rect(150, 78, 120, 20), cv::Scalar(40, 30, 30), cv::FILLED);
  const auto hidden = detectColourCues(img, kittiK(), kNormalCam, ColourCueSettings{});
  REQUIRE(hidden.size() == 1);
  CHECK(hidden[0].cls == CrowdClass::kTrafficLight);
}
