#include "mapfuse/stages/lsm_build.hpp"

#include <chrono>

#include "mapfuse/cli/params.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/io/lsm_io.hpp"
#include "mapfuse/io/output_transaction.hpp"
#include "mapfuse/io/picture_key.hpp"
#include "mapfuse/io/png_frames.hpp"
#include "mapfuse/io/stage_report.hpp"
#include "mapfuse/vehicle/render_topdown.hpp"

namespace mapfuse::stages {
namespace {

/// The top-down picture of the LSM, over the BEV images of the fallback perception if any.
cv::Mat renderLsm(const LoadedDrive& drive, const Lsm& lsm) {
  std::vector<vehicle::BevTile> tiles;
  const vehicle::LaneDetectSettings ls;
  for (std::size_t i = 0; i < drive.bev_images.size(); ++i)
    tiles.push_back({drive.bev_images[i], drive.T_odom_body[i] * drive.calib.T_body_cam,
                     drive.calib.ground, ls.bev_min_x, ls.bev_max_x, ls.bev_half_width,
                     ls.bev_resolution});
  const double res_m = tiles.empty() ? 0.2 : 0.05;
  return io::withPictureKey(vehicle::renderTopDown(lsm, drive.T_odom_body, res_m, tiles),
                            vehicle::topDownKey(lsm, res_m));
}

}  // namespace

nlohmann::json toJson(const vehicle::LsmBuildResult& r) {
  return {{"frames", r.frames},
          {"keyframes", r.keyframes},
          {"vp_frames", r.vp_frames},
          {"mean_pitch_correction_rad", r.mean_pitch_correction},
          {"vp_calibration",
           {{"pitch_rad", r.vp.fallback ? 0.0 : r.vp.median},
            {"estimated_pitch_rad", r.vp.median},
            {"spread_rad", r.vp.spread},
            {"standard_error_rad", r.vp.standard_error},
            {"supporting_frames", r.vp.accepted},
            {"frames_with_vp", r.vp.estimates},
            {"rejected_curve", r.vp.rejected_curve},
            {"rejected_azimuth", r.vp.rejected_azimuth},
            {"rejected_no_look_ahead", r.vp.rejected_no_look_ahead},
            {"azimuth_offset_rad", r.vp.azimuth_offset},
            {"fallback", r.vp.fallback},
            {"fallback_reason", r.vp.fallback_reason}}},
          {"body_tilt",
           {{"source", r.tilt.source},
            {"weighting", r.tilt.weighting},
            {"window_s", r.tilt.window},
            {"moves_height", r.tilt.moves_height},
            {"frames", r.tilt.frames},
            {"pitch_rms_rad", r.tilt.pitch_rms},
            {"roll_rms_rad", r.tilt.roll_rms},
            {"pitch_max_rad", r.tilt.pitch_max},
            {"roll_max_rad", r.tilt.roll_max},
            {"height_change_rms_m", r.tilt.height_change_rms}}},
          {"ego_motion_vs_gps",
           {{"fixes", r.gps_agreement.samples},
            {"length_m", r.gps_agreement.length},
            {"horizontal_rms_m", r.gps_agreement.horizontal_rms},
            {"vertical_rms_m", r.gps_agreement.vertical_rms},
            {"vertical_slope", r.gps_agreement.vertical_slope},
            {"scale_error", r.gps_agreement.scale_error}}},
          {"ranged_markings", r.ranged_markings},
          {"ranged_points", r.ranged_points},
          {"ranged_on_path", r.ranged_on_path},
          {"ground_instances", r.assembly.ground_instances},
          {"ground_instances_dropped", r.assembly.ground_dropped},
          {"line_samples", r.assembly.line_samples},
          {"line_samples_dropped_sigma", r.assembly.line_samples_dropped},
          {"aerial_tracks", r.aerial_tracks},
          {"aerial_triangulated", r.aerial_triangulated},
          {"aerial_rejected", r.aerial_rejected},
          {"aerial_unassociated_observations", r.aerial_unassociated_observations},
          {"elements", r.lsm.elements.size()},
          {"gps_fixes", r.lsm.gps.size()},
          {"seconds",
           {{"calibration", r.seconds_calibration},
            {"ranging", r.seconds_ranging},
            {"triangulation", r.seconds_triangulation},
            {"assembly", r.seconds_assembly},
            {"total", r.seconds_total}}}};
}

nlohmann::json toJson(const LsmBuildRun& run) {
  nlohmann::json summary = toJson(run.build);
  summary["drive_id"] = run.drive_id;
  summary["input_kind"] = run.input_kind;
  summary["semantics"] = run.semantics;
  summary["egomotion"] = run.egomotion;
  summary["lsm"] = run.lsm_file.filename().string();
  summary["converged"] = true;
  if (run.semantics == "segmenter") {
    summary["seconds"]["perception"] = run.perception_seconds;
    summary["seconds"]["network"] = run.network_seconds;
    summary["segmentation_cached_frames"] = run.cached_frames;
    summary["aerial_detections"] = run.aerial_detections;
    summary["lane_styles"] = {{"solid", run.lane_styles.solid},
                              {"dashed", run.lane_styles.dashed},
                              {"untyped", run.lane_styles.untyped},
                              {"dash_period_m", run.lane_styles.dash_period}};
  }
  return summary;
}

LsmBuildRun runLsmBuild(const LsmBuildInputs& in, const LsmBuildParams& p) {
  validateParams(p);
  if (in.out.empty()) throw ConfigError("lsm-build: no output folder given");
  io::OutputTransaction outputs(in.out);  // locked and writable before the work
  const auto t0 = std::chrono::steady_clock::now();
  const LoadedDrive drive = loadDrive(in, p);
  MAPFUSE_INFO("lsm-build: " << drive.drive_id << ": " << drive.frames.size() << " frames ("
                             << drive.input_kind << ", semantics " << drive.semantics
                             << ", ego-motion " << drive.egomotion << ")");
  LsmBuildRun run{in.out / (drive.drive_id + ".lsm." + p.format),
                  drive.drive_id,
                  drive.input_kind,
                  drive.semantics,
                  drive.egomotion,
                  drive.perception_seconds,
                  drive.network_seconds,
                  vehicle::buildLsm(drive, p.build)};
  run.cached_frames = drive.cached_frames;
  run.aerial_detections = drive.aerial_detections;
  run.lane_styles = drive.lane_styles;
  validateLsm(run.build.lsm, drive.drive_id);
  if (p.build.vanishing.enabled) {
    const auto& vp = run.build.vp;
    if (vp.fallback)
      MAPFUSE_INFO("lsm-build: " << drive.drive_id << ": VP calibration fell back to the static "
                                 << "extrinsic (" << vp.fallback_reason << ": " << vp.accepted
                                 << " supporting frames, median " << vp.median << " rad, spread "
                                 << vp.spread << " rad)");
    else
      MAPFUSE_INFO("lsm-build: " << drive.drive_id << ": VP calibration pitch " << vp.median
                                 << " rad from " << vp.accepted << " supporting frames (spread "
                                 << vp.spread << " rad)");
  }

  io::writeLsm(run.lsm_file, run.build.lsm);
  if (p.render)
    io::writePngFrame(in.out / (drive.drive_id + ".bev.png"), renderLsm(drive, run.build.lsm));
  nlohmann::json summary = toJson(run);
  summary["seconds"]["wall"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  io::writeResolvedConfig(in.out, "lsm-build", paramsToJson(p));
  io::writeSummary(in.out, "lsm-build", summary);
  outputs.commit();
  return run;
}

}  // namespace mapfuse::stages
