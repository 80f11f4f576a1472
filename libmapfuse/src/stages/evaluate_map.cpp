#include "mapfuse/stages/evaluate_map.hpp"

#include <algorithm>

#include "mapfuse/core/log.hpp"
#include "mapfuse/eval/map_report.hpp"
#include "mapfuse/eval/trajectory_metrics.hpp"
#include "mapfuse/geo/origin.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/lsm_io.hpp"
#include "mapfuse/io/map_png.hpp"
#include "mapfuse/io/stage_report.hpp"
#include "mapfuse/io/vector_map_io.hpp"

namespace mapfuse::stages {

void EvaluateMapParams::validate() const {
  const char* s = "EvaluateMapParams";
  requireParam(line_tolerance > 0, s, "line_tolerance", line_tolerance, "line_tolerance > 0");
  requireParam(discrete_tolerance > 0, s, "discrete_tolerance", discrete_tolerance,
               "discrete_tolerance > 0");
  requireParam(sample_step > 0, s, "sample_step", sample_step, "sample_step > 0");
  requireParam(lane_width_min >= 0, s, "lane_width_min", lane_width_min, "lane_width_min >= 0");
  requireParam(lane_width_max > lane_width_min, s, "lane_width_max", lane_width_max,
               "lane_width_max > lane_width_min");
  requireParam(neighbour_max_distance > 0, s, "neighbour_max_distance", neighbour_max_distance,
               "neighbour_max_distance > 0");
  requireParam(coverage_radius >= 0, s, "coverage_radius", coverage_radius, "coverage_radius >= 0");
  requireParam(coverage_range > 0, s, "coverage_range", coverage_range, "coverage_range > 0");
  requireParam(coverage_half_fov_deg > 0 && coverage_half_fov_deg <= 90, s, "coverage_half_fov_deg",
               coverage_half_fov_deg, "0 < coverage_half_fov_deg <= 90");
  requireParam(coverage_apex_x >= 0 && coverage_apex_x < coverage_range, s, "coverage_apex_x",
               coverage_apex_x, "0 <= coverage_apex_x < coverage_range");
  requireParam(rpe_distance > 0, s, "rpe_distance", rpe_distance, "rpe_distance > 0");
}

eval::MapEvalParams EvaluateMapParams::toEval() const {
  eval::MapEvalParams p;
  p.line_tolerance = line_tolerance;
  p.discrete_tolerance = discrete_tolerance;
  p.sample_step = sample_step;
  p.lane_width_min = lane_width_min;
  p.lane_width_max = lane_width_max;
  p.neighbour_max_distance = neighbour_max_distance;
  return p;
}

eval::CoverageWedge EvaluateMapParams::coverageWedge() const {
  return eval::CoverageWedge{coverage_radius, coverage_range, coverage_half_fov_deg * M_PI / 180.0,
                             coverage_apex_x};
}

int traversalsOf(const std::filesystem::path& map_file, const VectorMap& map) {
  const auto summary = map_file.parent_path() / "aggregate.summary.json";
  if (std::filesystem::exists(summary)) {
    const auto j = io::readDocument(summary);
    if (j.contains("inputs") && j["inputs"].contains("drives") &&
        j["inputs"]["drives"].is_number_integer())
      return j["inputs"]["drives"].get<int>();
  }
  int best = 0;
  for (const auto& i : map.instances) best = std::max(best, i.support.drives);
  return best;
}

nlohmann::json runEvaluateMap(const EvaluateMapInputs& in, const std::filesystem::path& out_dir,
                              const EvaluateMapParams& params) {
  if (in.maps.empty()) throw InputError("no map to evaluate (--map)");
  if (!in.traversals.empty() && in.traversals.size() != in.maps.size())
    throw InputError("--traversals needs one value per --map (" + std::to_string(in.maps.size()) +
                     " maps, " + std::to_string(in.traversals.size()) + " values)");
  if (!in.lsms.empty() && in.truth_trajectories.empty())
    throw InputError("--lsm needs --truth-trajectories (folder of <drive>.trajectory.json)");
  VectorMap truth = io::readVectorMap(in.truth);
  std::size_t coverage_files = 0;
  VectorMap unscored;  // truth outside the drives' view: map elements there are not scored
  unscored.origin = truth.origin;
  if (!in.truth_trajectories.empty() && params.coverage_radius > 0) {
    // score only what the drives could see: truth near the true trajectories
    if (!std::filesystem::is_directory(in.truth_trajectories))
      throw IoError(in.truth_trajectories, "not a folder of <drive>.trajectory.json files");
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(in.truth_trajectories)) {
      const std::string name = e.path().filename().string();
      if (name.size() > 16 && name.rfind(".trajectory.json") == name.size() - 16)
        files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());
    std::vector<Pose3> poses;
    for (const auto& f : files) {
      const auto t = eval::readTrueTrajectory(f);
      if (!geo::sameOrigin(t.origin, truth.origin))
        throw InputError(f.string() + ": origin differs from the truth map " + in.truth);
      for (const auto& p : t.poses) poses.push_back(p.T_enu_body);
    }
    coverage_files = files.size();
    truth = eval::clipToCoverage(truth, poses, params.coverageWedge(), &unscored);
  }
  std::vector<eval::MapReportEntry> entries;
  VectorMap last_map;
  for (std::size_t i = 0; i < in.maps.size(); ++i) {
    // in the truth's ENU once, for the metrics and the picture
    const VectorMap map = eval::inOrigin(io::readVectorMap(in.maps[i]), truth.origin);
    last_map = map;
    eval::MapReportEntry e;
    e.name = std::filesystem::path(in.maps[i]).filename().string();
    if (in.maps.size() > 1) e.name = in.maps[i];
    e.traversals = in.traversals.empty() ? traversalsOf(in.maps[i], map) : in.traversals[i];
    e.metrics = eval::evaluateMap(map, truth, params.toEval(), &unscored);
    entries.push_back(std::move(e));
  }
  std::vector<eval::TrajectoryMetrics> trajectories;
  for (const auto& f : in.lsms) {
    const Lsm lsm = io::readLsm(f);
    const auto truth_file =
        std::filesystem::path(in.truth_trajectories) / (lsm.drive_id + ".trajectory.json");
    if (!std::filesystem::exists(truth_file))
      throw IoError(truth_file.string(),
                    "true trajectory of drive '" + lsm.drive_id + "' not found");
    trajectories.push_back(
        eval::compareTrajectory(lsm, eval::readTrueTrajectory(truth_file), params.rpe_distance, f));
  }

  std::filesystem::create_directories(out_dir);
  nlohmann::json maps = nlohmann::json::array();
  for (const auto& e : entries)
    maps.push_back(
        {{"map", e.name}, {"traversals", e.traversals}, {"classes", eval::toJson(e.metrics)}});
  nlohmann::json traj = nlohmann::json::array();
  std::vector<double> ate;
  for (const auto& t : trajectories) {
    traj.push_back(eval::toJson(t));
    if (t.ate_translation.count) ate.push_back(t.ate_translation.rms);
  }
  nlohmann::json summary = {{"truth", in.truth},
                            {"truth_clipped_to_coverage", coverage_files > 0},
                            {"coverage_trajectories", coverage_files},
                            {"maps", maps},
                            {"trajectories", traj}};
  if (!ate.empty()) summary["trajectory_ate_rms_mean_m"] = eval::errorStats(ate).mean;
  io::writeBytesAtomic(out_dir / "evaluate.md", eval::markdownReport(entries, trajectories));
  eval::writeErrorPerClassPng(out_dir / "error_per_class.png", entries.back());
  {  // the (last) map in colour over the truth in grey
    std::vector<std::vector<Eigen::Vector3d>> background;
    for (const auto& t : truth.instances) background.push_back(t.points);
    io::writeMapPng(out_dir / "map_over_truth.png", last_map, background);
  }
  if (entries.size() > 1)
    eval::writeErrorVsTraversalsPng(out_dir / "error_vs_traversals.png", entries);
  io::writeResolvedConfig(out_dir, "evaluate", paramsToJson(params));
  io::writeSummary(out_dir, "evaluate", summary);
  MAPFUSE_INFO("evaluate map: " << entries.size() << " map(s), " << trajectories.size()
                                << " trajectories -> " << out_dir.string());
  return summary;
}

}  // namespace mapfuse::stages
