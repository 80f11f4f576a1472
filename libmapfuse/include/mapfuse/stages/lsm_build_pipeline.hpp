#pragma once
/// @file The processing half of lsm-build, after loading: vanishing-point calibration,
/// ranging (eq. 1), triangulation (eq. 2-3), keyframes and assembly. Separate from I/O so the
/// benchmark and tests can run it on in-memory drives.
#include <nlohmann/json.hpp>
#include <vector>

#include "mapfuse/core/lsm.hpp"
#include "mapfuse/stages/lsm_build_inputs.hpp"
#include "mapfuse/vehicle/camera.hpp"

namespace mapfuse::stages {

struct ProcessedDrive {
  Lsm lsm;
  std::vector<vehicle::GroundPlane> planes;  ///< per frame, after calibration
  std::vector<double> pitch_corrections;     ///< rad per frame (0 when calibration is off)
  int vp_frames = 0;                         ///< frames with a vanishing-point estimate
  nlohmann::json stats;                      ///< counts and timings for the summary
};

/// @brief Runs calibration, ranging, triangulation and assembly on a loaded drive.
ProcessedDrive processDrive(const LoadedDrive& drive, const LsmBuildParams& params);

}  // namespace mapfuse::stages
