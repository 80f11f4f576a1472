#pragma once
/// @file Stage `lsm-build` (Song et al. 2023 §3): a raw drive (docs/formats-frames.md, or a
/// KITTI raw drive with a poses file) -> one local semantic map (LSM) in the drive's odom
/// frame. Wires vehicle/: ego-motion, vanishing-point calibration, ground ranging (eq. 1),
/// aerial triangulation (eq. 2-3), LSM assembly; and the fallback perception for real images.
#include <filesystem>
#include <string>

#include "mapfuse/core/lsm.hpp"
#include "mapfuse/cli/params.hpp"

namespace mapfuse::stages {

struct LsmBuildParams {
  std::string input_kind = "auto";   ///< auto | frames | kitti_raw
  std::string semantics = "auto";    ///< auto | observations | masks | segmenter
  std::string egomotion = "auto";    ///< auto | imu_wheel | poses | oxts
  std::string poses_frame = "cam0";  ///< cam0 (KITTI odometry) | velo (lidar-semantic-map)
  std::string segmenter = "enet";    ///< fallback perception network: enet
  std::string model;                 ///< ENet model; "" = <shared>/models/enet-cityscapes/...
  double camera_height = 1.65;       ///< m, KITTI camera height (frames: from calibration)
  int kitti_last_frame = -1;         ///< KITTI: last frame index used (-1 = all)
  double wheel_scale = 1.0;          ///< multiplies wheel speeds
  double gyro_bias_x = 0.0, gyro_bias_y = 0.0, gyro_bias_z = 0.0;  ///< rad/s
  double keyframe_spacing = 10.0;                                  ///< m
  double keyframe_max_angle = 0.3;                                 ///< rad
  double min_range = 3.0, max_range = 30.0;                        ///< m, ground ranging band
  double sigma_pixel = 1.0;                                        ///< px
  double sigma_height = 0.03;                                      ///< m
  double sigma_attitude = 0.003;  ///< rad, residual pitch / roll after calibration
  double tilt_window = 2.0;       ///< s, body tilt from the ego-motion (body_tilt.hpp); 0: off
  bool vp_calibration = true;     ///< correct the ground plane from lane vanishing points
  int vp_window = 601;            ///< frames in the median window (the mount error is constant)
  double vp_max_range = 25.0;     ///< m, lane points used for line fits
  double vp_max_line_rms = 1.5;   ///< px
  double max_pitch_correction = 0.05;        ///< rad
  int mask_min_area = 20;                    ///< px, smaller mask components are noise
  double min_parallax = 0.02;                ///< rad
  int min_track_frames = 3;                  ///< frames for aerial triangulation
  double track_sigma_pixel = 1.0;            ///< px
  double huber_delta = 2.0;                  ///< sigmas
  double max_reprojection_rms = 4.0;         ///< px
  double max_track_range = 30.0;             ///< m, aerial tracks never seen closer are rejected
  double association_radius = 0.6;           ///< m
  double point_spacing = 0.5;                ///< m
  double max_element_length = 30.0;          ///< m
  int min_observations = 2;                  ///< frames per ground instance
  double keyframe_sigma_translation = 0.05;  ///< m
  double keyframe_sigma_rotation = 0.002;    ///< rad
  std::string format = "json";               ///< LSM encoding: json | cbor
  bool render = true;                        ///< write <drive>.bev.png (top-down picture)

  template <class V>
  void visit(V& v) {
    v("input_kind", input_kind, "", "auto, frames (simulate layout) or kitti_raw");
    v("semantics", semantics, "", "auto, observations, masks or segmenter (fallback perception)");
    v("egomotion", egomotion, "", "auto, imu_wheel, poses (needs --poses) or oxts");
    v("poses_frame", poses_frame, "",
      "frame of the --poses file: cam0 (KITTI odometry T_world_cam0) or velo (KITTI raw only: "
      "T_world_velo, e.g. lidar-semantic-map poses.txt)");
    v("segmenter", segmenter, "", "fallback segmentation network (enet)");
    v("model", model, "", "segmentation model file; empty = shared models/enet-cityscapes");
    v("camera_height", camera_height, "m", "KITTI camera height above the road");
    v("kitti_last_frame", kitti_last_frame, "", "KITTI: last frame index used (-1 = all)");
    v("wheel_scale", wheel_scale, "", "dead reckoning: wheel speed scale");
    v("gyro_bias_x", gyro_bias_x, "rad/s", "dead reckoning: gyro bias x");
    v("gyro_bias_y", gyro_bias_y, "rad/s", "dead reckoning: gyro bias y");
    v("gyro_bias_z", gyro_bias_z, "rad/s", "dead reckoning: gyro bias z");
    v("keyframe_spacing", keyframe_spacing, "m", "travelled distance between keyframes");
    v("keyframe_max_angle", keyframe_max_angle, "rad", "rotation that forces a keyframe");
    v("min_range", min_range, "m", "closest ranged ground point (eq. 1 band)");
    v("max_range", max_range, "m", "farthest ranged ground point (eq. 1 band)");
    v("sigma_pixel", sigma_pixel, "px", "marking pixel noise (covariances)");
    v("sigma_height", sigma_height, "m", "camera height uncertainty (covariances)");
    v("sigma_attitude", sigma_attitude, "rad", "pitch/roll uncertainty (covariances)");
    v("tilt_window", tilt_window, "s",
      "follow the body's pitch and roll from the ego-motion against their mean over this window; "
      "0: off");
    v("vp_calibration", vp_calibration, "", "vanishing-point ground-plane calibration");
    v("vp_window", vp_window, "frames", "median window of the pitch correction");
    v("vp_max_range", vp_max_range, "m", "lane points farther than this are not fitted");
    v("vp_max_line_rms", vp_max_line_rms, "px", "straightness required of a fitted lane");
    v("max_pitch_correction", max_pitch_correction, "rad", "larger corrections are outliers");
    v("mask_min_area", mask_min_area, "px", "smaller mask components are dropped");
    v("min_parallax", min_parallax, "rad", "aerial tracks with less parallax are rejected");
    v("min_track_frames", min_track_frames, "", "frames needed to triangulate a track");
    v("track_sigma_pixel", track_sigma_pixel, "px", "aerial key-point noise");
    v("huber_delta", huber_delta, "sigma", "robust loss threshold of the triangulation");
    v("max_reprojection_rms", max_reprojection_rms, "px", "worse tracks are rejected");
    v("max_track_range", max_track_range, "m", "aerial tracks never seen closer are rejected");
    v("association_radius", association_radius, "m", "spatial merge radius of id-less markings");
    v("point_spacing", point_spacing, "m", "resampling step along merged lines");
    v("max_element_length", max_element_length, "m", "longer lines are split");
    v("min_observations", min_observations, "", "frames needed to keep a ground instance");
    v("keyframe_sigma_translation", keyframe_sigma_translation, "m", "keyframe pose sigma");
    v("keyframe_sigma_rotation", keyframe_sigma_rotation, "rad", "keyframe pose sigma");
    v("format", format, "", "LSM encoding: json or cbor");
    v("render", render, "", "write a top-down PNG of the LSM");
  }
  void validate() const;
};

/// Command-line inputs that are not tunables.
struct LsmBuildInputs {
  std::filesystem::path drive;  ///< drive folder
  std::filesystem::path out;    ///< output folder
  std::filesystem::path poses;  ///< KITTI odometry poses file (egomotion = poses)
  std::string drive_id;         ///< override (KITTI: default = folder name)
};

struct LsmBuildResult {
  std::filesystem::path lsm_file;
  Lsm lsm;
  nlohmann::json summary;
};

/// @brief Runs the stage: writes <out>/<drive_id>.lsm.<format>, lsm-build.config.json,
/// lsm-build.summary.json and (render) <drive_id>.bev.png.
/// @throws IoError, ParseError, InputError (exit codes 4, 3, 3); ConfigError for bad params.
LsmBuildResult runLsmBuild(const LsmBuildInputs& inputs, const LsmBuildParams& params);

}  // namespace mapfuse::stages
