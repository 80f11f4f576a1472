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
#include "mapfuse/vehicle/lsm_build_summary.hpp"
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

nlohmann::json toJson(const LsmBuildRun& run) {
  nlohmann::json summary = vehicle::toJson(run.build);
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
                  vehicle::buildLsm(drive, p.build),
                  drive.cached_frames,
                  drive.aerial_detections,
                  drive.lane_styles};
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
