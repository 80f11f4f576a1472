#include <array>
#include <catch2/catch.hpp>
#include <map>

#include "mapfuse/core/classes.hpp"

using namespace mapfuse;

TEST_CASE("crowd class names round-trip and have the DESIGN geometry kinds", "[core][classes]") {
  for (int i = 0; i < kNumCrowdClasses; ++i) {
    const auto c = static_cast<CrowdClass>(i);
    REQUIRE(crowdClassFromName(crowdClassName(c)) == c);
  }
  CHECK(geometryKind(CrowdClass::kLaneLine) == GeometryKind::kLine);
  CHECK(geometryKind(CrowdClass::kStopLine) == GeometryKind::kLine);
  CHECK(geometryKind(CrowdClass::kGroundArrow) == GeometryKind::kPlanar);
  CHECK(geometryKind(CrowdClass::kCrosswalk) == GeometryKind::kPlanar);
  CHECK(geometryKind(CrowdClass::kTrafficSign) == GeometryKind::kPlanar);
  CHECK(geometryKind(CrowdClass::kPole) == GeometryKind::kPoint);
  CHECK(geometryKind(CrowdClass::kTrafficLight) == GeometryKind::kPoint);
  CHECK_FALSE(crowdClassFromName("lane"));
  CHECK(lineStyleFromName("dashed") == LineStyle::kDashed);
  CHECK(lineColorFromName("yellow") == LineColor::kYellow);
  CHECK_FALSE(lineStyleFromName("dotted"));
}

TEST_CASE("LiDAR classes map to the SemanticKITTI ids of DESIGN.md", "[core][classes]") {
  CHECK(semanticKittiId(LidarClass::kRoad) == 40);
  CHECK(semanticKittiId(LidarClass::kSidewalk) == 48);
  CHECK(semanticKittiId(LidarClass::kBuilding) == 50);
  CHECK(semanticKittiId(LidarClass::kFence) == 51);
  CHECK(semanticKittiId(LidarClass::kPole) == 80);
  CHECK(semanticKittiId(LidarClass::kVegetation) == 70);
  CHECK(semanticKittiId(LidarClass::kVehicle) == 10);
  CHECK(lidarClassFromSemanticKitti(60) == LidarClass::kRoad);  // lane marking counts as road
  for (int i = 0; i < kNumLidarClasses; ++i) {
    const auto c = static_cast<LidarClass>(i);
    CHECK(lidarClassFromSemanticKitti(semanticKittiId(c)) == c);
    CHECK(lidarClassFromName(lidarClassName(c)) == c);
  }
}

TEST_CASE("Cityscapes channels map onto the 8 LiDAR classes", "[core][classes]") {
  CHECK(lidarClassFromCityscapes(1) == LidarClass::kRoad);
  CHECK(lidarClassFromCityscapes(2) == LidarClass::kSidewalk);
  CHECK(lidarClassFromCityscapes(4) == LidarClass::kBuilding);     // wall
  CHECK(lidarClassFromCityscapes(8) == LidarClass::kPole);         // traffic sign
  CHECK(lidarClassFromCityscapes(10) == LidarClass::kVegetation);  // terrain
  CHECK(lidarClassFromCityscapes(11) == LidarClass::kUnlabeled);   // sky
  CHECK(lidarClassFromCityscapes(14) == LidarClass::kVehicle);     // car
  CHECK(lidarClassFromCityscapes(19) == LidarClass::kVehicle);     // bicycle
  CHECK(lidarClassFromCityscapes(20) == LidarClass::kUnlabeled);   // out of range
}

TEST_CASE("LiDAR class colours are SemanticKITTI's color_map converted from BGR to RGB",
          "[core][classes]") {
  // semantic-kitti.yaml color_map (B, G, R) of each class's SemanticKITTI id.
  const std::map<uint16_t, std::array<uint8_t, 3>> kBgr = {
      {0, {0, 0, 0}},      {10, {245, 150, 100}}, {40, {255, 0, 255}}, {48, {75, 0, 75}},
      {50, {0, 200, 255}}, {51, {50, 120, 255}},  {70, {0, 175, 0}},   {80, {150, 240, 255}}};
  for (int i = 0; i < kNumLidarClasses; ++i) {
    const auto c = static_cast<LidarClass>(i);
    const auto& bgr = kBgr.at(semanticKittiId(c));
    INFO(lidarClassName(c));
    CHECK(lidarClassColor(c) == std::array<uint8_t, 3>{bgr[2], bgr[1], bgr[0]});
  }
  // Cars blue, buildings orange (as SemanticKITTI's own pictures show them).
  const auto car = lidarClassColor(LidarClass::kVehicle);
  CHECK((car[2] > car[0] && car[2] > 200));
  const auto building = lidarClassColor(LidarClass::kBuilding);
  CHECK((building[0] == 255 && building[2] == 0));
}
