#pragma once
/// @file The semantic class registry (DESIGN.md "Semantic classes"): crowd vector classes with
/// their attributes and geometry kinds, and the LiDAR voxel classes with their mappings from
/// Cityscapes (CNN output) and to SemanticKITTI ids, and colour palettes.
#include <array>
#include <cstdint>
#include <optional>
#include <string>

namespace mapfuse {

// ---------------------------------------------------------------- crowd (vector) classes

/// Classes of the crowdsourced vector map (Song et al. 2023).
enum class CrowdClass : uint8_t {
  kLaneLine = 0,
  kStopLine,
  kGroundArrow,  ///< "LaneMarking" in the paper
  kCrosswalk,
  kTrafficSign,
  kTrafficLight,
  kPole,
};
constexpr int kNumCrowdClasses = 7;

/// How an element's points are to be read.
enum class GeometryKind : uint8_t {
  kLine,    ///< polyline (lane_line, stop_line)
  kPlanar,  ///< polygon / oriented rectangle (ground_arrow, crosswalk, traffic_sign)
  kPoint,   ///< a point with a height (pole, traffic_light)
};

enum class LineStyle : uint8_t { kNone = 0, kSolid, kDashed };
enum class LineColor : uint8_t { kNone = 0, kWhite, kYellow };

/// Attributes of an element or instance; only lane lines use them today.
struct Attributes {
  LineStyle style = LineStyle::kNone;
  LineColor color = LineColor::kNone;
  bool operator==(const Attributes& o) const { return style == o.style && color == o.color; }
};

/// @brief Canonical snake_case name ("lane_line", ...), as used in every file format.
const char* crowdClassName(CrowdClass c);
/// @brief Inverse of crowdClassName; nullopt for an unknown name.
std::optional<CrowdClass> crowdClassFromName(const std::string& name);
GeometryKind geometryKind(CrowdClass c);
/// @brief Display colour (R, G, B) for pictures on dark or photographic backgrounds (maps,
/// camera frames): lane lines white, poles grey.
std::array<uint8_t, 3> crowdClassColor(CrowdClass c);
/// @brief Display colour (R, G, B) on white paper (evaluate's charts): the same hue family where
/// the map colour reads on white, ink for white lane lines, violet for grey poles; every colour
/// has Rec. 601 luma <= 150 and the seven are pairwise distinct.
std::array<uint8_t, 3> crowdClassPaperColor(CrowdClass c);

const char* lineStyleName(LineStyle s);  ///< "none", "solid", "dashed"
const char* lineColorName(LineColor c);  ///< "none", "white", "yellow"
std::optional<LineStyle> lineStyleFromName(const std::string& name);
std::optional<LineColor> lineColorFromName(const std::string& name);

// ---------------------------------------------------------------- LiDAR (voxel) classes

/// The 8 labels of the LiDAR + camera pipeline (Jeong et al. 2018).
enum class LidarClass : uint8_t {
  kUnlabeled = 0,
  kRoad,
  kSidewalk,
  kBuilding,
  kFence,
  kPole,
  kVegetation,
  kVehicle,
};
constexpr int kNumLidarClasses = 8;

const char* lidarClassName(LidarClass c);  ///< "unlabeled", "road", ...
std::optional<LidarClass> lidarClassFromName(const std::string& name);
/// @brief Display colour (R, G, B): SemanticKITTI's palette of the class's id (its color_map
/// lists B, G, R; converted), e.g. vehicle (100, 150, 245) blue, building (255, 200, 0) orange.
std::array<uint8_t, 3> lidarClassColor(LidarClass c);

/// @brief SemanticKITTI semantic id written to .label files (road 40, sidewalk 48,
/// building 50, fence 51, pole 80, vegetation 70, vehicle -> car 10, unlabeled 0).
uint16_t semanticKittiId(LidarClass c);
/// @brief LiDAR class of a SemanticKITTI semantic id (lane-marking 60 counts as road,
/// other vehicles (13, 15, 16, 18, 20) as vehicle; moving ids 252.. as their static class;
/// everything else unlabeled).
LidarClass lidarClassFromSemanticKitti(uint16_t id);

/// Number of Cityscapes train classes the ENet model emits (including "Unlabeled" at 0).
constexpr int kNumCityscapesClasses = 20;
/// @brief LiDAR class of an ENet/Cityscapes output channel (enet-classes.txt order:
/// Unlabeled, Road, Sidewalk, Building, Wall, Fence, Pole, TrafficLight, TrafficSign,
/// Vegetation, Terrain, Sky, Person, Rider, Car, Truck, Bus, Train, Motorcycle, Bicycle).
/// Wall -> building, traffic light/sign -> pole, terrain -> vegetation,
/// car/truck/bus/train/motorcycle/bicycle -> vehicle; sky, person, rider -> unlabeled.
LidarClass lidarClassFromCityscapes(int channel);

}  // namespace mapfuse
