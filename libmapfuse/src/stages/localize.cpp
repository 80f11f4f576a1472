#include "mapfuse/stages/localize.hpp"

#include <map>

#include "mapfuse/cli/params.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/core/parallel_for.hpp"
#include "mapfuse/core/progress.hpp"
#include "mapfuse/eval/map_metrics.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/lsm_io.hpp"
#include "mapfuse/io/output_transaction.hpp"
#include "mapfuse/io/stage_report.hpp"
#include "mapfuse/io/vector_map_io.hpp"
#include "mapfuse/localize/lost_causes.hpp"
#include "mapfuse/localize/maps_by_origin.hpp"
#include "mapfuse/localize/report.hpp"

namespace mapfuse::stages {

LocalizeRun runLocalize(const LocalizeInputs& in, const std::filesystem::path& out_dir,
                        const LocalizeParams& params) {
  validateParams(params);
  io::OutputTransaction outputs(out_dir);  // locked and writable before the work
  if (in.lsms.empty()) throw InputError("localize: no drive (LSM) to localise");
  if (!in.lsm_build_config.empty() && in.frames_dir.empty())
    throw ConfigError("localize: --lsm-build-config is for the frames level (--frames)");
  const VectorMap file_map = io::readVectorMap(in.map);
  std::map<std::string, eval::TrueTrajectory> truth;
  if (!in.truth_trajectories.empty())
    for (auto& [file, t] : eval::readTrueTrajectories(in.truth_trajectories))
      truth[t.drive_id] = std::move(t);
  const std::vector<Lsm> lsms = io::readLsmInputs(in.lsms);  // duplicates refused (exit 2)
  const std::size_t n = lsms.size();
  std::vector<localize::DriveObservations> obs;
  std::vector<localize::MapInDriveFrame> map_of(n);  // the map in each drive's ENU
  std::vector<const eval::TrueTrajectory*> true_of(n, nullptr);
  std::optional<VectorMap> truth_map;
  if (!in.truth_map.empty()) truth_map = io::readVectorMap(in.truth_map);
  localize::MapsByOrigin maps(file_map, truth_map, params.localize);
  for (std::size_t i = 0; i < n; ++i) {  // every input checked before the work
    if (lsms[i].keyframes.empty())
      throw InputError(in.lsms[i] + ": field 'keyframes': no keyframes: nothing to localise");
    if (in.frames_dir.empty())
      obs.push_back(
          localize::observationsOf(lsms[i], params.localize.match_attributes, in.lsms[i]));
    else
      obs.push_back(frameLevelObservations(in, lsms[i], params));
    map_of[i] = maps.at(*lsms[i].origin);
    if (in.truth_trajectories.empty()) continue;
    const auto t = truth.find(lsms[i].drive_id);
    if (t == truth.end())
      throw IoError(in.truth_trajectories,
                    "true trajectory of drive '" + lsms[i].drive_id + "' not found");
    true_of[i] = &t->second;
  }
  LocalizeRun run;
  run.level = in.frames_dir.empty() ? "lsm" : "frames";
  run.solve = params.smoother.solve;
  localize::LocalizeSettings settings = params.localize;
  if (!in.frames_dir.empty()) settings.window = params.frames.frame_window;
  run.drives.resize(n);
  Progress progress("drives", n);
  parallelFor(n, [&](std::size_t i) {  // drives are independent
    LocalizedDrive& d = run.drives[i];
    d.file = in.lsms[i];
    d.drive_id = lsms[i].drive_id;
    d.result = localize::localizeDrive(*map_of[i].index, obs[i], settings);
    if (params.smoother.solve == "full_drive")
      localize::smoothDrive(*map_of[i].index, obs[i], settings, params.smoother, d.result);
    d.map_to_truth = map_of[i].map_to_truth;
    if (true_of[i])
      d.errors = localize::localizeErrors(
          d.result, *true_of[i], *lsms[i].origin, d.file,
          map_of[i].map_to_truth ? map_of[i].map_to_truth->T_truth_map : Pose3::Identity());
    progress.advance();
  });
  for (std::size_t i = 0; i < n; ++i) {
    const LocalizedDrive& d = run.drives[i];
    const Lsm& lsm = lsms[i];
    const std::string name =
        lsm.drive_id.empty() ? std::filesystem::path(d.file).stem().string() : lsm.drive_id;
    io::writeDocument(
        out_dir / (name + ".trajectory.json"),
        localize::trajectoryJson(d.result, lsm.drive_id, lsm.vehicle_id, *lsm.origin));
    if (d.errors) {
      io::writeBytesAtomic(out_dir / (name + ".errors.csv"), localize::errorsCsv(*d.errors));
      localize::writeErrorPlot(out_dir / (name + ".errors.png"), *d.errors,
                               "localize " + name + ": error vs distance");
    }
    run.keyframes += d.result.keyframes.size();
    run.lost += static_cast<std::size_t>(d.result.lost);
    run.seconds_localize += d.result.seconds;
  }
  progress.finish();
  const double share = run.lostShare();
  std::vector<std::pair<std::string, const localize::LocalizeResult*>> by_drive;
  for (const auto& d : run.drives) by_drive.emplace_back(d.file, &d.result);
  const std::string why = localize::lostDiagnosis(by_drive, settings.min_matches);
  if (share > params.lost.max_lost_share)  // before commit: the previous outputs stay
    throw InputError(why + " (share " + std::to_string(share) + " > max_lost_share " +
                     std::to_string(params.lost.max_lost_share) + ", map " + in.map + ")");
  if (share > params.lost.warn_lost_share) MAPFUSE_WARN("localize: " << why);
  nlohmann::json summary = toJson(run);
  summary["lost_diagnosis"] = why;
  summary["map"] = in.map;
  summary["lost_warning"] = share > params.lost.warn_lost_share;
  io::writeResolvedConfig(out_dir, "localize", paramsToJson(params));
  io::writeSummary(out_dir, "localize", summary);
  outputs.commit();
  MAPFUSE_INFO("localize: " << run.drives.size() << " drive(s), " << run.keyframes << " keyframes, "
                            << run.lost << " lost -> " << out_dir.string());
  return run;
}

}  // namespace mapfuse::stages
