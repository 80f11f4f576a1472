#pragma once
/// @file The LSM of one drive (Song et al. 2023 §3): per-frame ground planes tilted with the body
/// and calibrated from lane vanishing points (§3.2.1), ground ranging (eq. 1), aerial
/// triangulation (eq. 2-3), keyframes and assembly (§3.3), on a drive already loaded (camera
/// calibration, ego-motion, per-frame semantics). Stage `lsm-build` reads the drive and writes
/// the result; tests and the benchmark call buildLsm on drives in memory.
#include <map>
#include <string>
#include <vector>

#include "mapfuse/core/drive_records.hpp"
#include "mapfuse/core/lsm.hpp"
#include "mapfuse/core/param.hpp"
#include "mapfuse/vehicle/dead_reckoning.hpp"
#include "mapfuse/vehicle/ground_ranging.hpp"
#include "mapfuse/vehicle/lsm_assembly.hpp"
#include "mapfuse/vehicle/triangulation.hpp"
#include "mapfuse/vehicle/vanishing_point.hpp"
#include "mapfuse/vehicle/vp_gate.hpp"

namespace mapfuse::vehicle {

/// A drive ready for buildLsm: one entry per camera frame in stamps, T_odom_body and frames.
struct DriveData {
  std::string drive_id, vehicle_id;
  CameraCalib calib;
  std::vector<double> stamps;             ///< s, per frame
  std::vector<Pose3> T_odom_body;         ///< ego-motion, per frame
  std::vector<FrameObservations> frames;  ///< semantics, per frame
  std::vector<GpsFix> gps;                ///< copied into the LSM
};

/// Parameters of buildLsm; each declared once, in the visit() of the struct that owns it.
struct LsmBuildSettings {
  KeyframeSettings keyframes;
  RangingSettings ranging;
  double tilt_window = 4.0;  ///< s, body tilt from the ego-motion (body_tilt.hpp); 0: off
  std::string tilt_weighting = "hann";  ///< "box" | "hann": weights of the frames in the window
  bool tilt_moves_height = true;        ///< the camera height follows the tilt (lever arm)
  VanishingSettings vanishing;
  TriangulationSettings triangulation;
  AssemblySettings assembly;

  template <class V>
  void visit(V& v) {
    keyframes.visit(v);
    ranging.visit(v);
    v("tilt_window", tilt_window, "s",
      "follow the body's pitch and roll from the ego-motion against their mean over this window; "
      "0: off",
      param::in(0, 3600));
    v("tilt_weighting", tilt_weighting, "",
      "weights of the frames in tilt_window: hann (cos^2 taper, a suspension oscillation above "
      "2/tilt_window Hz leaks < 3 %) or box (equal)",
      param::oneOf({"box", "hann"}));
    v("tilt_moves_height", tilt_moves_height, "",
      "move the camera height with the body tilt (the body pivots about its origin, the camera "
      "sits T_body_cam from it)");
    vanishing.visit(v);
    v.relation("vp_max_range", vanishing.max_range, vanishing.max_range > ranging.min_range,
               "> min_range");
    triangulation.visit(v);
    assembly.visit(v);
  }
};

/// The body attitude the ground planes follow (lsm-build.summary.json "body_tilt"): the road
/// normal from the ego-motion over tilt_window, and what it changed per frame.
struct BodyTiltStats {
  std::string source = "off";    ///< "ego-motion" or "off" (tilt_window 0)
  std::string weighting;         ///< "box" | "hann"
  double window = 0.0;           ///< s
  bool moves_height = false;     ///< the camera height followed the tilt
  int frames = 0;                ///< frames tilted
  double pitch_rms = 0.0;        ///< rad, applied tilt about the body y axis, RMS over frames
  double roll_rms = 0.0;         ///< rad, about the body x axis
  double pitch_max = 0.0;        ///< rad, largest |pitch| applied
  double roll_max = 0.0;         ///< rad, largest |roll| applied
  double height_change_rms = 0;  ///< m, camera height change, RMS over frames
};

/// What buildLsm made and counted (lsm-build.summary.json).
struct LsmBuildResult {
  Lsm lsm;                                ///< in the drive's odom frame
  std::vector<GroundPlane> planes;        ///< per frame, after tilt and calibration
  std::vector<double> pitch_corrections;  ///< rad per frame (0 when calibration is off)
  int vp_frames = 0;                      ///< frames supporting the VP calibration
  VpCalibration vp;                       ///< the VP gate's counts and decision
  BodyTiltStats tilt;                     ///< the body attitude the planes follow
  double mean_pitch_correction = 0.0;     ///< rad
  int frames = 0, keyframes = 0;
  int ranged_markings = 0;  ///< ground markings ranged in single frames
  int ranged_points = 0;    ///< their points (eq. 1)
  int ranged_on_path = 0;   ///< ... of them ranged on the road ahead (path_surface.hpp)
  AssemblyStats assembly;   ///< ground instances merged and dropped
  int aerial_tracks = 0, aerial_triangulated = 0;
  std::map<std::string, int> aerial_rejected;  ///< tracks per rejection reason
  int aerial_unassociated_observations = 0;    ///< boxes without a track id
  /// s, wall time of each step
  double seconds_calibration = 0, seconds_ranging = 0, seconds_triangulation = 0,
         seconds_assembly = 0, seconds_total = 0;
};

/// @brief Builds the LSM of a drive: ground planes, ranging (eq. 1), triangulation (eq. 2-3),
/// keyframes and assembly (§3.3). Frames are processed in parallel (OpenMP).
LsmBuildResult buildLsm(const DriveData& drive, const LsmBuildSettings& settings);

/// @brief Per frame, the nominal ground plane tilted with the body over `tilt_window` and, when
/// enabled, corrected by the median-smoothed vanishing-point pitch of the frames the gate accepts
/// (§3.2.1, vp_gate.hpp). Fills planes, pitch_corrections, vp and vp_frames of `result`.
void calibrateGroundPlanes(const DriveData& drive, const LsmBuildSettings& settings,
                           LsmBuildResult& result);

/// @brief Eq. (1) for every ground observation of every frame, in the odom frame, on the frame's
/// plane (calibrateGroundPlanes) and, when `path_surface` is on, on the road ahead as the drive's
/// path shows it (vehicle/path_surface.hpp); markings with too few points in the range band
/// (planar 1, lines 2) are dropped. `points` / `on_path`, when given, count the ranged points
/// and those ranged on the road ahead.
std::vector<RangedMarking> rangeMarkings(const DriveData& drive,
                                         const std::vector<GroundPlane>& planes,
                                         const RangingSettings& settings, int* points = nullptr,
                                         int* on_path = nullptr);

}  // namespace mapfuse::vehicle
