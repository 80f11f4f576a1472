#pragma once
/// @file Association of aerial boxes across frames when the detector gives no track ids
/// (Song et al. 2023 §3.2.3): pyramidal Lucas-Kanade optical flow (cv::calcOpticalFlowPyrLK)
/// of points inside each box of the previous frame predicts where the box moved; the box of
/// the next frame with the best overlap (IoU) inherits the track id.
#include <cstdint>
#include <filesystem>
#include <opencv2/core.hpp>
#include <vector>

#include "mapfuse/core/drive_records.hpp"

namespace mapfuse::vehicle {

struct FlowSettings {
  int grid = 4;            ///< flow points per box side (grid x grid)
  int window = 21;         ///< px, LK window
  int pyramid_levels = 3;  ///< LK pyramid levels
  double min_iou = 0.3;    ///< overlap needed to continue a track
  /// px: for the IoU test, box sides shorter than this are widened about the box centre, so a
  /// thin pole (a few px wide) moving a few px still overlaps its next box; 0 = off
  double min_box_side = 0.0;
  /// frames a track may go unseen (missed detections) and still continue: its box is carried
  /// on by the flow of the frames between; 0 = only consecutive frames
  int max_gap = 0;
};

/// @brief Gives every box in `next` a track id: the id of the flowed `prev` box it overlaps
/// most (same class and detector, IoU >= min_iou), else a fresh id from `next_id` (incremented).
/// `prev` boxes must already carry ids. Images are 8-bit grey of equal size.
/// @param moved when given, receives the flowed box of every `prev` box (next frame's pixels)
void associateByFlow(const cv::Mat& prev_gray, const cv::Mat& next_gray,
                     const std::vector<AerialObservation>& prev,
                     std::vector<AerialObservation>& next, int64_t& next_id,
                     const FlowSettings& settings, std::vector<Eigen::Vector4d>* moved = nullptr);

/// @brief Gives the aerial boxes of a whole drive track ids: fresh ids in the first frame, then
/// associateByFlow between each pair of consecutive images (one per frame); tracks unseen for
/// up to settings.max_gap frames take part with their flowed last box.
/// @throws IoError / ParseError for a missing or undecodable image.
void associateAerialByFlow(const std::vector<std::filesystem::path>& images,
                           std::vector<FrameObservations>& frames,
                           const FlowSettings& settings = FlowSettings{});

/// @brief Intersection over union of two boxes (u_min, v_min, u_max, v_max).
double boxIou(const Eigen::Vector4d& a, const Eigen::Vector4d& b);

}  // namespace mapfuse::vehicle
