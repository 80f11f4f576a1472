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
};

/// @brief Gives every box in `next` a track id: the id of the flowed `prev` box it overlaps
/// most (same class, IoU >= min_iou), else a fresh id from `next_id` (incremented).
/// `prev` boxes must already carry ids. Images are 8-bit grey of equal size.
void associateByFlow(const cv::Mat& prev_gray, const cv::Mat& next_gray,
                     const std::vector<AerialObservation>& prev,
                     std::vector<AerialObservation>& next, int64_t& next_id,
                     const FlowSettings& settings);

/// @brief Gives the aerial boxes of a whole drive track ids: fresh ids in the first frame, then
/// associateByFlow (FlowSettings{}) between each pair of consecutive images (one per frame).
/// @throws IoError / ParseError for a missing or undecodable image.
void associateAerialByFlow(const std::vector<std::filesystem::path>& images,
                           std::vector<FrameObservations>& frames);

/// @brief Intersection over union of two boxes (u_min, v_min, u_max, v_max).
double boxIou(const Eigen::Vector4d& a, const Eigen::Vector4d& b);

}  // namespace mapfuse::vehicle
