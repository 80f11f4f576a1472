#pragma once
/// @file What lsm-build loads before processing, independent of the input layout
/// (simulate frames folder or KITTI raw drive): calibration, per-frame stamps, poses and
/// semantics. Used by stages/lsm_build.cpp and the benchmark.
#include <filesystem>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "mapfuse/core/lsm.hpp"
#include "mapfuse/stages/lsm_build.hpp"
#include "mapfuse/vehicle/camera.hpp"
#include "mapfuse/vehicle/observations.hpp"

namespace mapfuse::stages {

struct LoadedDrive {
  std::string drive_id, vehicle_id;
  vehicle::CameraCalib calib;
  std::vector<double> stamps;                      ///< s, per frame
  std::vector<Pose3> T_odom_body;                  ///< per frame
  std::vector<vehicle::FrameObservations> frames;  ///< semantics per frame
  std::vector<GpsFix> gps;
  std::vector<std::filesystem::path> images;     ///< per frame (KITTI), may be empty
  std::vector<cv::Mat> bev_images;               ///< per frame BEV grey (segmenter only)
  std::string input_kind, semantics, egomotion;  ///< what was actually used
  double perception_seconds = 0.0;               ///< fallback perception time (network incl.)
  double network_seconds = 0.0;                  ///< of which the segmentation network
};

/// @brief Loads a drive according to the params (auto-detection of layout, semantics and
/// ego-motion source). @throws IoError, ParseError, InputError, ConfigError.
LoadedDrive loadDrive(const LsmBuildInputs& inputs, const LsmBuildParams& params);

}  // namespace mapfuse::stages
