#pragma once
/// @file Aerial detections from colour and shape cues in the image (issue 21), independent of
/// the segmentation network's class: ENet labels the sfnd drive's no-stopping sign as the truck
/// behind it and sees its lit signal heads in a few frames only (docs/lsm-build.md, "Real camera
/// frames"). Two cues, both above the horizon (road users and their lamps are below it):
///  - a prohibition sign: a red ring (a red component whose upper half-circle, with the box width
///    as diameter, lies on red pixels, and whose box is mostly not red), key point its centre;
///  - a lit signal lamp: a small bright red blob inside a dark housing (most pixels of a box
///    three times its size dark), key point its centre.
/// The boxes are tracked by optical flow and triangulated (eq. 2-3) like the network's.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "mapfuse/core/drive_records.hpp"
#include "mapfuse/core/param.hpp"

namespace mapfuse::vehicle {

/// Thresholds of the colour cues; declared once, in visit().
struct ColourCueSettings {
  bool enabled = true;               ///< detect red rings and lit red lamps
  int min_saturation = 100;          ///< HSV saturation (0-255) of a "red" pixel
  int min_value = 60;                ///< HSV value (0-255) of a "red" pixel
  int ring_min_diameter = 12;        ///< px, ring box width
  int ring_max_diameter = 80;        ///< px
  double ring_min_arc = 0.6;         ///< share of the upper half-circle on the component
  double ring_max_fill = 0.45;       ///< red pixels / box area (a disc or a panel is fuller)
  double ring_min_visible = 0.6;     ///< box height / width: at most the lower 40 % hidden
  int lamp_min_area = 8;             ///< px
  int lamp_max_side = 14;            ///< px
  int lamp_min_peak = 200;           ///< HSV value (0-255) of the lamp's brightest pixel
  double lamp_min_dark_share = 0.7;  ///< of the 3x box around the lamp (the housing)
  int lamp_dark_value = 90;          ///< HSV value below which a pixel is dark
  int horizon_margin = 10;           ///< px, cues must end this far above the horizon row

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("colour_cues", enabled, "",
      "also detect prohibition signs (red ring) and lit signal lamps (red in a dark housing) "
      "from colour and shape, above the horizon");
    v("cue_min_saturation", min_saturation, "", "HSV saturation (0-255) of a red pixel",
      in(0, 255));
    v("cue_min_value", min_value, "", "HSV value (0-255) of a red pixel", in(0, 255));
    v("ring_min_diameter", ring_min_diameter, "px", "smaller red rings are dropped", in(3, 10000));
    v("ring_max_diameter", ring_max_diameter, "px", "larger red rings are dropped", in(3, 10000));
    v.relation("ring_max_diameter", ring_max_diameter, ring_max_diameter >= ring_min_diameter,
               ">= ring_min_diameter");
    v("ring_min_arc", ring_min_arc, "",
      "share of the upper half-circle (box width as diameter) that must be red", in(0, 1));
    v("ring_max_fill", ring_max_fill, "", "red share of the ring's box above which it is a disc",
      in(0, 1));
    v("ring_min_visible", ring_min_visible, "",
      "ring box height / width below which too much of the sign is hidden", in(0, 1));
    v("lamp_min_area", lamp_min_area, "px", "smaller red lamps are dropped", in(1, 10000));
    v("lamp_max_side", lamp_max_side, "px", "red blobs with a longer side are not lamps",
      in(1, 10000));
    v("lamp_min_peak", lamp_min_peak, "", "HSV value (0-255) a lit lamp reaches", in(0, 255));
    v("lamp_min_dark_share", lamp_min_dark_share, "",
      "share of dark pixels in the box three times the lamp's (its housing)", in(0, 1));
    v("lamp_dark_value", lamp_dark_value, "", "HSV value (0-255) below which a pixel is dark",
      in(0, 255));
    v("cue_horizon_margin", horizon_margin, "px",
      "colour cues must end this far above the horizon row (vehicle lights are below it)",
      in(-10000, 10000));
  }
};

/// @brief Red rings (traffic_sign) and lit red lamps (traffic_light) above the horizon of the
/// nominal ground plane; no track ids yet. Each observation's single key point is the centre.
/// @param bgr 8-bit colour image
/// @param ground_normal_cam unit normal of the nominal ground plane in the camera frame
std::vector<AerialObservation> detectColourCues(const cv::Mat& bgr, const Eigen::Matrix3d& K,
                                                const Eigen::Vector3d& ground_normal_cam,
                                                const ColourCueSettings& settings);

/// @brief Row of the horizon (rays parallel to the ground plane) at column `u`; +inf when the
/// camera looks straight down or up.
double horizonRow(double u, const Eigen::Matrix3d& K, const Eigen::Vector3d& ground_normal_cam);

}  // namespace mapfuse::vehicle
