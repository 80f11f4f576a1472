#pragma once
/// @file Built-in fallback perception for users without a lane network (issue 6, item 6):
/// the road area from a Cityscapes segmentation network (ENet through OpenCV DNN), then lane
/// markings inside it by white top-hat (bright-ridge) filtering in a bird's-eye view (BEV) of
/// the nominal ground plane, thinned to centre lines and projected back to image pixels so the
/// rest of lsm-build (vanishing-point calibration, eq. 1) treats them like any lane input.
/// Issue 21: road users (vehicle and person classes) are masked out of the markings and the
/// BEV; signs, lights and poles become aerial boxes (aerial_detection.hpp), tracked by flow.
#include <filesystem>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "mapfuse/core/drive_records.hpp"
#include "mapfuse/core/param.hpp"
#include "mapfuse/vehicle/aerial_colour.hpp"
#include "mapfuse/vehicle/aerial_detection.hpp"
#include "mapfuse/vehicle/camera.hpp"
#include "mapfuse/vehicle/line_style.hpp"

namespace mapfuse::vehicle {

/// How lsm-build perceives frames that come without observations: ground-marking masks
/// (centerline.hpp) or camera images through this fallback perception. Declared once, in visit().
struct PerceptionSettings {
  std::string segmenter = "enet";  ///< fallback perception network
  std::string model;               ///< ENet model; "" = <shared>/models/enet-cityscapes/...
  int mask_min_area = 20;          ///< px, smaller mask components are noise
  std::string segmentation_cache;  ///< folder of <frame>.seg.png class maps; "" = none
  int road_user_margin = 6;        ///< px, road-user mask dilation (outline, shadow edge)
  AerialDetectSettings aerial;     ///< signs, lights, poles from the segmentation
  ColourCueSettings colour;        ///< signs and lights from colour and shape (not the network)
  LineStyleSettings line_style;    ///< solid / dashed typing of the lane lines
  double track_min_box_side = 16;  ///< px, FlowSettings::min_box_side of the segmenter's boxes
  int track_max_gap = 5;           ///< frames, FlowSettings::max_gap of the segmenter's boxes

  template <class V>
  void visit(V& v) {
    v("segmenter", segmenter, "", "fallback segmentation network", param::oneOf({"enet"}));
    v("model", model, "", "segmentation model file; empty = shared models/enet-cityscapes");
    v("mask_min_area", mask_min_area, "px", "smaller mask components are dropped",
      param::in(1, 100000000));
    v("segmentation_cache", segmentation_cache, "",
      "folder of the network's class maps (<image>.seg.png): read when present, else computed "
      "and written there; empty = no cache");
    v("road_user_margin", road_user_margin, "px",
      "dilation of the vehicle/person mask kept free of markings and of the BEV mosaic",
      param::in(0, 1000));
    aerial.visit(v);
    colour.visit(v);
    line_style.visit(v);
    v("track_min_box_side", track_min_box_side, "px",
      "segmenter boxes: sides shorter than this are widened for the frame-to-frame IoU test "
      "(thin poles)",
      param::in(0, 10000));
    v("track_max_gap", track_max_gap, "frames",
      "segmenter boxes: a track missed in this many consecutive frames still continues",
      param::in(0, 1000));
  }
};

/// @brief Reads a colour image. @throws IoError when missing, ParseError when undecodable.
cv::Mat readColorImage(const std::filesystem::path& path);

/// The network's answer for one image.
struct Segmentation {
  cv::Mat classes;     ///< CV_8U Cityscapes train id per pixel
  cv::Mat confidence;  ///< CV_8U winning-class softmax probability x 255 per pixel
};

/// ENet (Torch7) road segmentation through cv::dnn.
class RoadSegmenter {
 public:
  /// @throws IoError when the model file is missing or cannot be loaded.
  explicit RoadSegmenter(const std::filesystem::path& model);
  ~RoadSegmenter();
  /// @brief Cityscapes class id per pixel (CV_8U, image size): RGB/255 input at native scale,
  /// reflect-padded to a multiple of 16.
  cv::Mat classify(const cv::Mat& bgr);
  /// @brief classify() with the winning class's softmax probability per pixel.
  Segmentation segment(const cv::Mat& bgr);
  /// @brief 255 where the class is road (Cityscapes train id 1 in enet-classes.txt order).
  cv::Mat roadMask(const cv::Mat& bgr);

 private:
  struct Impl;  // keeps opencv2/dnn out of this header
  std::unique_ptr<Impl> impl_;
};

struct LaneDetectSettings {
  double bev_min_x = 4.0;        ///< m, nearest BEV row (forward)
  double bev_max_x = 30.0;       ///< m, farthest BEV row
  double bev_half_width = 10.0;  ///< m, lateral half extent
  double bev_resolution = 0.05;  ///< m per BEV pixel
  double tophat_width = 0.6;     ///< m, structuring element (wider than a marking)
  double min_contrast = 12.0;    ///< grey levels, minimal top-hat response
  double contrast_sigmas = 3.0;  ///< threshold = max(min_contrast, mean + k sigma) on the road
  double road_margin = 0.4;      ///< m, road mask dilation (markings on the road edge)
  double min_length = 1.5;       ///< m, shorter blobs are not markings
  double max_width = 0.45;       ///< m, wider blobs are not markings (mean width)
  double sample_step = 0.25;     ///< m, spacing of the centre-line samples
  LineStyleSettings style;       ///< solid / dashed typing (line_style.hpp)
};

/// Result of the lane detector for one frame.
struct LaneDetection {
  std::vector<GroundObservation> lanes;  ///< lane_line centre lines in image pixels
  cv::Mat bev_gray;                      ///< BEV of the image (row 0 = far, col 0 = left)
  cv::Mat bev_road;                      ///< BEV of the road mask
  cv::Mat bev_markings;                  ///< BEV binary marking mask (after filtering)
  std::vector<std::vector<Eigen::Vector2d>> lanes_ground;  ///< (forward, left) m on the plane
  std::vector<PieceStyle> styles;  ///< per lane: solid / dashed and its evidence (line_style.hpp)
};

/// @brief Lane markings inside `road_mask` (CV_8U, 255 = road) of `bgr`, in the BEV of the
/// calibration's nominal ground plane. Pixels of `road_users` (CV_8U, 255 = masked; may be
/// empty) are kept out of the markings and are 0 (= not seen) in bev_gray, so the mosaic fills
/// them from other frames. Each lane piece is typed solid / dashed (settings.style).
LaneDetection detectLanes(const cv::Mat& bgr, const cv::Mat& road_mask, const CameraCalib& calib,
                          const LaneDetectSettings& settings, const cv::Mat& road_users = {});

/// The lane pieces of a drive by style (line_style.hpp), over all frames.
struct LaneStyleCounts {
  int solid = 0, dashed = 0, untyped = 0;  ///< lane pieces (one per marking component and frame)
  double dash_period = 0.0;  ///< m, median dash + gap over the frames that measured one; 0 = none
};

/// Lane lines the fallback perception found in every frame of a drive.
struct LanePerception {
  std::vector<FrameObservations> frames;  ///< index, stamp, lane lines and aerial boxes per image
  std::vector<cv::Mat> bev_images;        ///< BEV grey per image (for the top-down picture)
  double seconds = 0.0;                   ///< s, perception, network included
  double network_seconds = 0.0;           ///< s, of which the segmentation network
  int cached_frames = 0;                  ///< segmentations read from the cache
  int aerial_detections = 0;              ///< sign/light/pole boxes over all frames
  LaneStyleCounts lane_styles;            ///< lane pieces typed solid / dashed over all frames
};

/// @brief Segmentation (ENet, `model`, or settings.segmentation_cache), road users masked, BEV
/// lane detection (LaneDetectSettings{}) and aerial boxes (settings.aerial, settings.colour) on
/// each image, one
/// after the other: the network uses OpenCV's own threads. The model is loaded only when a
/// frame is not in the cache.
/// @param stamps s per image
/// @throws IoError when the model or an image is missing, ParseError when undecodable (also a
/// cached class map of the wrong size or type).
LanePerception perceiveFrames(const std::vector<std::filesystem::path>& images,
                              const std::vector<double>& stamps, const CameraCalib& calib,
                              const std::filesystem::path& model,
                              const PerceptionSettings& settings);

}  // namespace mapfuse::vehicle
