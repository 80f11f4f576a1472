#pragma once
/// @file Frames-level observations (docs/localize.md "Frames level"): a raw drive localised frame
/// by frame. Per camera frame, its own ground markings ranged on its ground plane by lsm-build's
/// per-frame path (eq. 1, vehicle::rangeMarkings: lane / stop line points, arrow and crosswalk
/// centres), and the aerial elements (signs, lights, poles) that lsm-build triangulated over
/// several frames (eq. 2-3), at the frame of their keyframe; the frame's prior pose is the
/// georeferenced keyframe nearest in time moved by the drive's own odometry to the frame.
#include <string>
#include <vector>

#include "mapfuse/core/lsm.hpp"
#include "mapfuse/core/param.hpp"
#include "mapfuse/localize/localizer.hpp"
#include "mapfuse/vehicle/lsm_assembly.hpp"
#include "mapfuse/vehicle/lsm_build.hpp"

namespace mapfuse::localize {

struct FrameLevelSettings {
  double frame_point_spacing = 2.0;  ///< m, a frame's line points thinned to this spacing
  double frame_window = 2.0;         ///< m travelled either side, frames level (replaces window)

  template <class V>
  void visit(V& v) {
    v("frame_point_spacing", frame_point_spacing, "m",
      "frames level: a frame's ranged line points are thinned to this spacing along the line",
      param::in(0, 100));
    v("frame_window", frame_window, "m",
      "frames level: observations of the frames within this travelled distance join (window of "
      "the LSM level)",
      param::in(0, 200));
  }
};

/// @brief The per-frame observations of a raw drive, ready for localizeDrive.
/// @param drive the drive as lsm-build reads it (stages::loadDrive): per frame its stamp,
/// odometry T_odom_body and semantics.
/// @param markings the drive's ground markings ranged frame by frame (vehicle::rangeMarkings),
/// odom frame.
/// @param lsm the LSM lsm-build made of this drive, georeferenced (frame enu): its keyframes give
/// the frames' priors, its signs / lights / poles the aerial observations.
/// @throws InputError naming `source` when the LSM is not in enu, is another drive's, or a
/// keyframe stamp is not a frame of the drive (the LSM was not built from it).
DriveObservations frameObservationsOf(const vehicle::DriveData& drive,
                                      const std::vector<vehicle::RangedMarking>& markings,
                                      const Lsm& lsm, const FrameLevelSettings& settings,
                                      bool use_attributes, const std::string& source);

}  // namespace mapfuse::localize
