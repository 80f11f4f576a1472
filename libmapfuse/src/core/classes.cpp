#include "mapfuse/core/classes.hpp"

namespace mapfuse {
namespace {

struct CrowdInfo {
  const char* name;
  GeometryKind kind;
  std::array<uint8_t, 3> color;  // on dark backgrounds (maps, camera frames)
  std::array<uint8_t, 3> paper;  // on white paper (charts): luma <= 150, pairwise distinct
};
constexpr std::array<CrowdInfo, kNumCrowdClasses> kCrowd{{
    {"lane_line", GeometryKind::kLine, {255, 255, 255}, {40, 40, 40}},  // white -> ink
    {"stop_line", GeometryKind::kLine, {255, 60, 60}, {220, 40, 40}},
    {"ground_arrow", GeometryKind::kPlanar, {0, 200, 255}, {0, 150, 210}},
    {"crosswalk", GeometryKind::kPlanar, {255, 200, 0}, {225, 135, 0}},
    {"traffic_sign", GeometryKind::kPlanar, {220, 220, 0}, {150, 150, 0}},
    {"traffic_light", GeometryKind::kPoint, {250, 170, 30}, {140, 70, 20}},
    {"pole", GeometryKind::kPoint, {153, 153, 153}, {140, 80, 190}},  // grey -> violet
}};

struct LidarInfo {
  const char* name;
  uint16_t kitti_id;
  std::array<uint8_t, 3> color;
};
// Colours: SemanticKITTI's semantic-kitti.yaml `color_map` of the class's id, which lists
// B, G, R (its visualiser hands the triples to OpenCV); stored here as R, G, B.
constexpr std::array<LidarInfo, kNumLidarClasses> kLidar{{
    {"unlabeled", 0, {0, 0, 0}},       // color_map[0]  = [0, 0, 0]
    {"road", 40, {255, 0, 255}},       // color_map[40] = [255, 0, 255]
    {"sidewalk", 48, {75, 0, 75}},     // color_map[48] = [75, 0, 75]
    {"building", 50, {255, 200, 0}},   // color_map[50] = [0, 200, 255]
    {"fence", 51, {255, 120, 50}},     // color_map[51] = [50, 120, 255]
    {"pole", 80, {255, 240, 150}},     // color_map[80] = [150, 240, 255]
    {"vegetation", 70, {0, 175, 0}},   // color_map[70] = [0, 175, 0]
    {"vehicle", 10, {100, 150, 245}},  // color_map[10] = [245, 150, 100]
}};

constexpr std::array<LidarClass, kNumCityscapesClasses> kFromCityscapes{{
    LidarClass::kUnlabeled,   // Unlabeled
    LidarClass::kRoad,        // Road
    LidarClass::kSidewalk,    // Sidewalk
    LidarClass::kBuilding,    // Building
    LidarClass::kBuilding,    // Wall
    LidarClass::kFence,       // Fence
    LidarClass::kPole,        // Pole
    LidarClass::kPole,        // TrafficLight
    LidarClass::kPole,        // TrafficSign
    LidarClass::kVegetation,  // Vegetation
    LidarClass::kVegetation,  // Terrain
    LidarClass::kUnlabeled,   // Sky
    LidarClass::kUnlabeled,   // Person
    LidarClass::kUnlabeled,   // Rider
    LidarClass::kVehicle,     // Car
    LidarClass::kVehicle,     // Truck
    LidarClass::kVehicle,     // Bus
    LidarClass::kVehicle,     // Train
    LidarClass::kVehicle,     // Motorcycle
    LidarClass::kVehicle,     // Bicycle
}};

}  // namespace

const char* crowdClassName(CrowdClass c) {
  return kCrowd[static_cast<int>(c)].name;
}
GeometryKind geometryKind(CrowdClass c) {
  return kCrowd[static_cast<int>(c)].kind;
}
std::array<uint8_t, 3> crowdClassColor(CrowdClass c) {
  return kCrowd[static_cast<int>(c)].color;
}
std::array<uint8_t, 3> crowdClassPaperColor(CrowdClass c) {
  return kCrowd[static_cast<int>(c)].paper;
}

std::optional<CrowdClass> crowdClassFromName(const std::string& name) {
  for (int i = 0; i < kNumCrowdClasses; ++i)
    if (name == kCrowd[i].name) return static_cast<CrowdClass>(i);
  return std::nullopt;
}

const char* lineStyleName(LineStyle s) {
  switch (s) {
    case LineStyle::kSolid: return "solid";
    case LineStyle::kDashed: return "dashed";
    default: return "none";
  }
}
const char* lineColorName(LineColor c) {
  switch (c) {
    case LineColor::kWhite: return "white";
    case LineColor::kYellow: return "yellow";
    default: return "none";
  }
}
std::optional<LineStyle> lineStyleFromName(const std::string& name) {
  for (LineStyle s : {LineStyle::kNone, LineStyle::kSolid, LineStyle::kDashed})
    if (name == lineStyleName(s)) return s;
  return std::nullopt;
}
std::optional<LineColor> lineColorFromName(const std::string& name) {
  for (LineColor c : {LineColor::kNone, LineColor::kWhite, LineColor::kYellow})
    if (name == lineColorName(c)) return c;
  return std::nullopt;
}

const char* lidarClassName(LidarClass c) {
  return kLidar[static_cast<int>(c)].name;
}
std::array<uint8_t, 3> lidarClassColor(LidarClass c) {
  return kLidar[static_cast<int>(c)].color;
}
uint16_t semanticKittiId(LidarClass c) {
  return kLidar[static_cast<int>(c)].kitti_id;
}

std::optional<LidarClass> lidarClassFromName(const std::string& name) {
  for (int i = 0; i < kNumLidarClasses; ++i)
    if (name == kLidar[i].name) return static_cast<LidarClass>(i);
  return std::nullopt;
}

LidarClass lidarClassFromSemanticKitti(uint16_t id) {
  switch (id) {
    case 40:
    case 60: return LidarClass::kRoad;
    case 48: return LidarClass::kSidewalk;
    case 50: return LidarClass::kBuilding;
    case 51: return LidarClass::kFence;
    case 80:
    case 81: return LidarClass::kPole;
    case 70:
    case 72: return LidarClass::kVegetation;
    case 10:
    case 13:
    case 15:
    case 16:
    case 18:
    case 20:
    case 252:
    case 256:
    case 257:
    case 258:
    case 259: return LidarClass::kVehicle;
    default: return LidarClass::kUnlabeled;
  }
}

LidarClass lidarClassFromCityscapes(int channel) {
  if (channel < 0 || channel >= kNumCityscapesClasses) return LidarClass::kUnlabeled;
  return kFromCityscapes[channel];
}

}  // namespace mapfuse
