#pragma once
/// @file `evaluate map` (§5, Song et al. 2023): vector map(s) against the ground-truth map
/// (eval::evaluateMap, the truth clipped to what the drives could see with eval::clipToCoverage),
/// optionally trajectories of aligned LSMs against the true trajectories
/// (eval::compareTrajectory). Writes evaluate.summary.json, evaluate.config.json, evaluate.md and
/// PNG plots (docs/evaluate.md).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mapfuse/eval/map_metrics.hpp"
#include "mapfuse/eval/map_metrics_checks.hpp"
#include "mapfuse/eval/map_report.hpp"
#include "mapfuse/eval/trajectory_metrics.hpp"

namespace mapfuse::stages {

struct EvaluateMapParams {
  static constexpr const char* kName = "EvaluateMapParams";
  eval::MapEvalParams metrics;
  eval::TrajectoryEvalSettings trajectories;
  eval::CoverageWedge coverage;
  bool strict = false;  ///< refuse (exit 3) inputs that cannot be scored, instead of a warning

  template <class V>
  void visit(V& v) {
    metrics.visit(v);
    trajectories.visit(v);
    coverage.visit(v);
    v("strict", strict, "",
      "refuse (exit 3) an empty truth, an empty map or a map that does not overlap the truth "
      "(default: a warning and a 'problems' list in the summary)");
  }
};

struct EvaluateMapInputs {
  std::vector<std::string> maps;   ///< one or more vector maps (JSON/CBOR)
  std::string truth;               ///< ground-truth vector map
  std::vector<std::string> lsms;   ///< aligned LSMs for trajectory metrics (optional)
  std::string truth_trajectories;  ///< folder of <drive>.trajectory.json (needed with lsms)
  std::vector<int> traversals;     ///< per map (optional; else read beside the map)
};

/// What one `evaluate map` run found.
struct EvaluateMapRun {
  std::string truth;                       ///< the truth map file
  std::size_t coverage_trajectories = 0;   ///< true trajectories the truth was clipped to
  std::vector<eval::MapReportEntry> maps;  ///< per map, in input order
  std::vector<eval::TrajectoryMetrics> trajectories;  ///< per LSM, in input order
  std::vector<std::string> problems;  ///< eval::mapEvaluationProblems of every map (warned)
};

/// @brief The summary evaluate.summary.json holds.
nlohmann::json toJson(const EvaluateMapRun& run);
/// Largest number of traversals read from an aggregate summary.
constexpr int64_t kMaxTraversals = 1000000;

/// @brief Number of traversals behind a map: "inputs.drives" of aggregate.summary.json in the
/// map's folder when present, else the largest instance support (0 for an empty map).
/// @throws ParseError naming the summary and the field when inputs.drives is there but is not an
/// integer in [0, kMaxTraversals]; IoError / ParseError when the summary cannot be read.
int traversalsOf(const std::filesystem::path& map_file, const VectorMap& map);

/// @brief Runs the evaluation and writes the outputs into `out_dir`.
/// @throws ConfigError (parameters), IoError, ParseError, InputError (e.g. --lsm without
/// --truth-trajectories; with `strict`, inputs that cannot be scored).
EvaluateMapRun runEvaluateMap(const EvaluateMapInputs& inputs, const std::filesystem::path& out_dir,
                              const EvaluateMapParams& params);

}  // namespace mapfuse::stages
