#pragma once
/// @file Aerial detections from a semantic segmentation (issue 21): the pixels of the Cityscapes
/// classes pole, traffic light and traffic sign (ENet, fallback_perception.hpp) are grouped into
/// 8-connected components; each component large enough becomes one box with a confidence
/// (mean winning-class probability over its pixels), ready for the flow association
/// (flow_association.hpp) and the triangulation of eq. 2-3 (triangulation.hpp).
/// Road users (vehicle and person classes) give the mask that keeps ground markings and the
/// bird's-eye mosaic off them.
#include <opencv2/core.hpp>
#include <vector>

#include "mapfuse/core/drive_records.hpp"
#include "mapfuse/core/param.hpp"

namespace mapfuse::vehicle {

/// Channels of the ENet model: the line of models/enet-cityscapes/enet-classes.txt minus one
/// (line 1 "Unlabeled" = 0, "Road" = 1, "Pole" = 6, "TrafficLight" = 7, "TrafficSign" = 8).
namespace cityscapes {
constexpr int kRoad = 1, kPole = 6, kTrafficLight = 7, kTrafficSign = 8, kPerson = 12, kRider = 13,
              kCar = 14, kTruck = 15, kBus = 16, kTrain = 17, kMotorcycle = 18, kBicycle = 19;
}  // namespace cityscapes

/// Thresholds of the aerial detector; declared once, in visit().
struct AerialDetectSettings {
  bool enabled = true;               ///< detect signs, lights and poles in the segmentation
  int min_area = 100;                ///< px, smaller components are noise
  double min_confidence = 0.5;       ///< mean winning-class probability of a component
  int min_pole_height = 40;          ///< px, shorter pole components are clutter
  double min_pole_elongation = 3.0;  ///< box height / width of a pole component
  int border_margin = 2;             ///< px, components touching the image side borders are cut
  double max_road_user_share = 0.3;  ///< of the pixels around a component (ring of 3 px)
  int pole_merge_gap = 40;           ///< px, pole pieces one above the other closer are one pole

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("aerial_detection", enabled, "",
      "signs, lights and poles from the segmentation of real frames (then flow, eq. 2-3)");
    v("aerial_min_area", min_area, "px", "smaller sign/light/pole components are dropped",
      in(1, 1000000));
    v("aerial_min_confidence", min_confidence, "",
      "components with a lower mean class probability are dropped", in(0, 1));
    v("pole_min_height", min_pole_height, "px", "shorter pole components are dropped",
      in(1, 100000));
    v("pole_min_elongation", min_pole_elongation, "",
      "pole components less elongated (box height / width) are dropped", in(0, 1000));
    v("aerial_border_margin", border_margin, "px",
      "components this close to the left/right image border are cut off and dropped", in(0, 10000));
    v("aerial_max_road_user_share", max_road_user_share, "",
      "components whose surroundings (3 px ring around the box) are more road user than this "
      "are parts of vehicles (tail lights, stickers) and dropped",
      in(0, 1));
    v("pole_merge_gap", pole_merge_gap, "px",
      "pole components overlapping in columns and this close vertically are one pole (a pole "
      "cut by a bridge or a sign)",
      in(0, 100000));
  }
};

/// @brief The sign, light and pole components of one frame as boxes (no track ids yet).
/// @param classes CV_8U Cityscapes class per pixel
/// @param confidence CV_8U winning-class probability x 255 per pixel (same size)
/// @return one observation per component kept; confidence in [0, 1]
std::vector<AerialObservation> detectAerial(const cv::Mat& classes, const cv::Mat& confidence,
                                            const AerialDetectSettings& settings);

/// @brief Sets the key point of every pole to its axis at the camera's height: the box's centre
/// column on the row where camera rays run parallel to the ground plane (n . K^-1 x = 0). That
/// 3D point is the same in every frame while the pole's base hides behind vehicles and its top
/// leaves the image, so eq. 2-3 place the pole by it; its height stays unknown (0).
/// @param ground_normal_cam the nominal ground plane's unit normal in the camera frame
void setPoleAxisKeyPoints(std::vector<AerialObservation>& observations, const Eigen::Matrix3d& K,
                          const Eigen::Vector3d& ground_normal_cam);

/// @brief 255 where a road user is (person, rider, car, truck, bus, train, motorcycle,
/// bicycle), dilated by `margin_px` (their outline and shadow edge); CV_8U, size of `classes`.
cv::Mat roadUserMask(const cv::Mat& classes, int margin_px);

}  // namespace mapfuse::vehicle
