#include "mapfuse/stages/lsm_build.hpp"

#include <chrono>

#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/io/lsm_io.hpp"
#include "mapfuse/io/png_frames.hpp"
#include "mapfuse/io/stage_report.hpp"
#include "mapfuse/stages/lsm_build_inputs.hpp"
#include "mapfuse/stages/lsm_build_pipeline.hpp"
#include "mapfuse/vehicle/fallback_perception.hpp"
#include "mapfuse/vehicle/render_topdown.hpp"

namespace mapfuse::stages {

void LsmBuildParams::validate() const {
  const char* S = "LsmBuildParams";
  auto oneOf = [&](const char* field, const std::string& v, std::initializer_list<const char*> ok) {
    bool found = false;
    std::string rule = "one of";
    for (const char* o : ok) found = found || v == o, rule += std::string(" ") + o;
    requireParam(found, S, field, v, rule.c_str());
  };
  oneOf("input_kind", input_kind, {"auto", "frames", "kitti_raw"});
  oneOf("semantics", semantics, {"auto", "observations", "masks", "segmenter"});
  oneOf("egomotion", egomotion, {"auto", "imu_wheel", "poses", "oxts"});
  oneOf("poses_frame", poses_frame, {"cam0", "velo"});
  oneOf("segmenter", segmenter, {"enet"});
  oneOf("format", format, {"json", "cbor"});
  requireParam(camera_height > 0.0, S, "camera_height", camera_height, "> 0");
  requireParam(kitti_last_frame >= -1, S, "kitti_last_frame", kitti_last_frame, ">= -1");
  requireParam(wheel_scale > 0.0, S, "wheel_scale", wheel_scale, "> 0");
  requireParam(keyframe_spacing > 0.0, S, "keyframe_spacing", keyframe_spacing, "> 0");
  requireParam(keyframe_max_angle > 0.0, S, "keyframe_max_angle", keyframe_max_angle, "> 0");
  requireParam(min_range >= 0.0, S, "min_range", min_range, ">= 0");
  requireParam(max_range > min_range, S, "max_range", max_range, "> min_range");
  requireParam(sigma_pixel > 0.0, S, "sigma_pixel", sigma_pixel, "> 0");
  requireParam(sigma_height >= 0.0, S, "sigma_height", sigma_height, ">= 0");
  requireParam(sigma_attitude >= 0.0, S, "sigma_attitude", sigma_attitude, ">= 0");
  requireParam(vp_window >= 1, S, "vp_window", vp_window, ">= 1");
  requireParam(tilt_window >= 0, S, "tilt_window", tilt_window, ">= 0");
  requireParam(vp_max_range > min_range, S, "vp_max_range", vp_max_range, "> min_range");
  requireParam(vp_max_line_rms > 0.0, S, "vp_max_line_rms", vp_max_line_rms, "> 0");
  requireParam(max_pitch_correction > 0.0, S, "max_pitch_correction", max_pitch_correction, "> 0");
  requireParam(mask_min_area >= 1, S, "mask_min_area", mask_min_area, ">= 1");
  requireParam(min_parallax >= 0.0, S, "min_parallax", min_parallax, ">= 0");
  requireParam(max_track_range > 0.0, S, "max_track_range", max_track_range, "> 0");
  requireParam(min_track_frames >= 2, S, "min_track_frames", min_track_frames, ">= 2");
  requireParam(track_sigma_pixel > 0.0, S, "track_sigma_pixel", track_sigma_pixel, "> 0");
  requireParam(huber_delta > 0.0, S, "huber_delta", huber_delta, "> 0");
  requireParam(max_reprojection_rms > 0.0, S, "max_reprojection_rms", max_reprojection_rms, "> 0");
  requireParam(association_radius > 0.0, S, "association_radius", association_radius, "> 0");
  requireParam(point_spacing > 0.0, S, "point_spacing", point_spacing, "> 0");
  requireParam(max_element_length > point_spacing, S, "max_element_length", max_element_length,
               "> point_spacing");
  requireParam(min_observations >= 1, S, "min_observations", min_observations, ">= 1");
  requireParam(keyframe_sigma_translation > 0.0, S, "keyframe_sigma_translation",
               keyframe_sigma_translation, "> 0");
  requireParam(keyframe_sigma_rotation > 0.0, S, "keyframe_sigma_rotation", keyframe_sigma_rotation,
               "> 0");
}

LsmBuildResult runLsmBuild(const LsmBuildInputs& in, const LsmBuildParams& p) {
  p.validate();
  if (in.out.empty()) throw ConfigError("lsm-build: no output folder given");
  const auto t0 = std::chrono::steady_clock::now();
  const LoadedDrive drive = loadDrive(in, p);
  MAPFUSE_INFO("lsm-build: " << drive.drive_id << ": " << drive.frames.size() << " frames ("
                             << drive.input_kind << ", semantics " << drive.semantics
                             << ", ego-motion " << drive.egomotion << ")");
  ProcessedDrive proc = processDrive(drive, p);
  validateLsm(proc.lsm, drive.drive_id);

  LsmBuildResult res;
  res.lsm_file = in.out / (drive.drive_id + ".lsm." + p.format);
  io::writeLsm(res.lsm_file, proc.lsm);
  if (p.render) {
    std::vector<vehicle::BevTile> tiles;
    const vehicle::LaneDetectSettings ls;
    for (std::size_t i = 0; i < drive.bev_images.size(); ++i)
      tiles.push_back({drive.bev_images[i], drive.T_odom_body[i] * drive.calib.T_body_cam,
                       drive.calib.ground, ls.bev_min_x, ls.bev_max_x, ls.bev_half_width,
                       ls.bev_resolution});
    const double res_m = tiles.empty() ? 0.2 : 0.05;
    const cv::Mat img = vehicle::renderTopDown(proc.lsm, drive.T_odom_body, res_m, tiles);
    io::writePngFrame(in.out / (drive.drive_id + ".bev.png"),
                      io::withPictureKey(img, vehicle::topDownKey(proc.lsm, res_m)));
  }
  res.summary = proc.stats;
  res.summary["drive_id"] = drive.drive_id;
  res.summary["input_kind"] = drive.input_kind;
  res.summary["semantics"] = drive.semantics;
  res.summary["egomotion"] = drive.egomotion;
  res.summary["lsm"] = res.lsm_file.filename().string();
  res.summary["converged"] = true;
  if (drive.semantics == "segmenter")
    res.summary["seconds"]["perception"] = drive.perception_seconds,
    res.summary["seconds"]["network"] = drive.network_seconds;
  res.summary["seconds"]["wall"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  io::writeResolvedConfig(in.out, "lsm-build", paramsToJson(p));
  io::writeSummary(in.out, "lsm-build", res.summary);
  res.lsm = std::move(proc.lsm);
  return res;
}

}  // namespace mapfuse::stages
