#include "mapfuse/stages/evaluate_map.hpp"

#include <algorithm>

#include "mapfuse/cli/params.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/eval/input_problems.hpp"
#include "mapfuse/eval/scored_truth.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/json_view.hpp"
#include "mapfuse/io/map_png.hpp"
#include "mapfuse/io/output_transaction.hpp"
#include "mapfuse/io/stage_report.hpp"
#include "mapfuse/io/vector_map_io.hpp"

namespace mapfuse::stages {
namespace {

void checkInputs(const EvaluateMapInputs& in) {
  if (in.maps.empty()) throw InputError("no map to evaluate (--map)");
  if (!in.traversals.empty() && in.traversals.size() != in.maps.size())
    throw InputError("--traversals needs one value per --map (" + std::to_string(in.maps.size()) +
                     " maps, " + std::to_string(in.traversals.size()) + " values)");
  if (!in.lsms.empty() && in.truth_trajectories.empty())
    throw InputError("--lsm needs --truth-trajectories (folder of <drive>.trajectory.json)");
}

// evaluate.md and the plots: error per class of the last map, the last map in colour over the
// (scored) truth in grey, error versus traversals when there are several maps.
void writeReport(const std::filesystem::path& out_dir, const EvaluateMapRun& run,
                 const VectorMap& last_map, const VectorMap& truth) {
  io::writeBytesAtomic(out_dir / "evaluate.md", eval::markdownReport(run.maps, run.trajectories));
  eval::writeErrorPerClassPng(out_dir / "error_per_class.png", run.maps.back());
  std::vector<std::vector<Eigen::Vector3d>> background;
  for (const auto& t : truth.instances) background.push_back(t.points);
  io::MapPngOptions png;
  png.title = "map (colours) over the truth (grey)";
  png.background_label = "truth";
  io::writeMapPng(out_dir / "map_over_truth.png", last_map, background, png);
  if (run.maps.size() > 1)
    eval::writeErrorVsTraversalsPng(out_dir / "error_vs_traversals.png", run.maps);
}

}  // namespace

nlohmann::json toJson(const EvaluateMapRun& run) {
  nlohmann::json maps = nlohmann::json::array();
  for (const auto& e : run.maps)
    maps.push_back(
        {{"map", e.name}, {"traversals", e.traversals}, {"classes", eval::toJson(e.metrics)}});
  nlohmann::json traj = nlohmann::json::array();
  std::vector<double> ate;
  for (const auto& t : run.trajectories) {
    traj.push_back(eval::toJson(t));
    if (t.ate_translation.count) ate.push_back(t.ate_translation.rms);
  }
  nlohmann::json summary = {{"truth", run.truth},
                            {"truth_clipped_to_coverage", run.coverage_trajectories > 0},
                            {"coverage_trajectories", run.coverage_trajectories},
                            {"maps", maps},
                            {"trajectories", traj},
                            {"problems", run.problems}};
  if (!ate.empty()) summary["trajectory_ate_rms_mean_m"] = eval::errorStats(ate).mean;
  return summary;
}

int traversalsOf(const std::filesystem::path& map_file, const VectorMap& map) {
  const auto summary = map_file.parent_path() / "aggregate.summary.json";
  if (std::filesystem::exists(summary)) {
    // checked like every reader (unchecked, 4294967301 drives were read as 5)
    const io::Json j = io::readDocument(summary);
    const io::JsonView doc(j, summary.string());
    if (const auto inputs = doc.find("inputs"))
      if (const auto drives = inputs->find("drives"))
        return static_cast<int>(drives->integer(0, kMaxTraversals));
  }
  int best = 0;
  for (const auto& i : map.instances) best = std::max(best, i.support.drives);
  return best;
}

EvaluateMapRun runEvaluateMap(const EvaluateMapInputs& in, const std::filesystem::path& out_dir,
                              const EvaluateMapParams& params) {
  validateParams(params);
  checkInputs(in);
  io::OutputTransaction outputs(out_dir);  // locked and writable before the work
  eval::ScoredTruth scored = eval::scoredTruth(io::readVectorMap(in.truth), in.truth,
                                               in.truth_trajectories, params.coverage);
  EvaluateMapRun run{in.truth, scored.coverage_trajectories, {}, {}, {}};
  const VectorMap& truth = scored.scored;
  const auto observed = eval::observedTruth(scored, in.lsms);  // once, for every map
  VectorMap last_map;
  for (std::size_t i = 0; i < in.maps.size(); ++i) {
    const VectorMap map = eval::inOrigin(io::readVectorMap(in.maps[i]), truth.origin);  // once
    last_map = map;
    eval::MapReportEntry e;
    e.name =
        in.maps.size() > 1 ? in.maps[i] : std::filesystem::path(in.maps[i]).filename().string();
    e.traversals = in.traversals.empty() ? traversalsOf(in.maps[i], map) : in.traversals[i];
    eval::warnOrRefuse(eval::mapEvaluationProblems(map, in.maps[i], truth, in.truth), params.strict,
                       "evaluate map", run.problems);
    e.metrics = eval::scoreMap(map, scored, observed, params.metrics);
    run.maps.push_back(std::move(e));
  }
  for (const auto& f : in.lsms)
    run.trajectories.push_back(
        eval::compareLsmToTruth(f, in.truth_trajectories, params.trajectories));
  std::filesystem::create_directories(out_dir);
  writeReport(out_dir, run, last_map, truth);
  io::writeResolvedConfig(out_dir, "evaluate", paramsToJson(params));
  io::writeSummary(out_dir, "evaluate", toJson(run));
  outputs.commit();
  MAPFUSE_INFO("evaluate map: " << run.maps.size() << " map(s), " << run.trajectories.size()
                                << " trajectories -> " << out_dir.string());
  return run;
}

}  // namespace mapfuse::stages
