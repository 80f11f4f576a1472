#pragma once
/// @file `evaluate map` (§5, Song et al. 2023): vector map(s) against the ground-truth map,
/// optionally trajectories of aligned LSMs against the true trajectories. Writes
/// evaluate.summary.json, evaluate.config.json, evaluate.md and PNG plots (docs/evaluate.md).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mapfuse/cli/params.hpp"
#include "mapfuse/eval/map_metrics.hpp"

namespace mapfuse::stages {

struct EvaluateMapParams {
  double line_tolerance = 1.0;            ///< m
  double discrete_tolerance = 1.5;        ///< m
  double sample_step = 0.5;               ///< m
  double lane_width_min = 2.0;            ///< m
  double lane_width_max = 6.0;            ///< m
  double neighbour_max_distance = 100.0;  ///< m
  double rpe_distance = 10.0;             ///< m
  double coverage_radius = 12.0;          ///< m, 0 = evaluate against the whole truth
  double coverage_range = 22.0;           ///< m, forward reach of the coverage wedge
  double coverage_half_fov_deg = 31.0;    ///< deg, half opening of the coverage wedge
  double coverage_apex_x = 1.8;           ///< m, the wedge's apex (camera) ahead of the body

  template <class V>
  void visit(V& v) {
    v("line_tolerance", line_tolerance, "m", "lane-line samples within this distance match");
    v("discrete_tolerance", discrete_tolerance, "m",
      "largest centre distance of a matched discrete element");
    v("sample_step", sample_step, "m", "spacing of lane-line samples (stations)");
    v("lane_width_min", lane_width_min, "m", "neighbouring lines closer than this are not a lane");
    v("lane_width_max", lane_width_max, "m", "neighbouring lines farther than this are not a lane");
    v("neighbour_max_distance", neighbour_max_distance, "m",
      "discrete elements farther apart are not neighbours");
    v("rpe_distance", rpe_distance, "m", "travelled distance of the relative pose error");
    v("coverage_radius", coverage_radius, "m",
      "with --truth-trajectories: score only truth within this distance of a true trajectory "
      "(0 = whole truth)");
    v("coverage_range", coverage_range, "m",
      "with --truth-trajectories: how far ahead of a true pose the truth counts as seen");
    v("coverage_half_fov_deg", coverage_half_fov_deg, "deg",
      "with --truth-trajectories: half opening of the seen wedge ahead of a true pose (the "
      "camera's field of view; 90 = everything ahead)");
    v("coverage_apex_x", coverage_apex_x, "m",
      "with --truth-trajectories: the wedge's apex, the camera, this far ahead of the body "
      "origin (the simulator's mount)");
  }
  /// @throws ConfigError naming the field, the value and the rule.
  void validate() const;
  eval::MapEvalParams toEval() const;
  eval::CoverageWedge coverageWedge() const;
};

struct EvaluateMapInputs {
  std::vector<std::string> maps;   ///< one or more vector maps (JSON/CBOR)
  std::string truth;               ///< ground-truth vector map
  std::vector<std::string> lsms;   ///< aligned LSMs for trajectory metrics (optional)
  std::string truth_trajectories;  ///< folder of <drive>.trajectory.json (needed with lsms)
  std::vector<int> traversals;     ///< per map (optional; else read beside the map)
};

/// @brief Number of traversals behind a map: "inputs.drives" of aggregate.summary.json in the
/// map's folder when present, else the largest instance support (0 for an empty map).
int traversalsOf(const std::filesystem::path& map_file, const VectorMap& map);

/// @brief Runs the evaluation and writes the outputs into `out_dir`. @return the summary.
/// @throws IoError, ParseError, InputError (e.g. --lsm without --truth-trajectories).
nlohmann::json runEvaluateMap(const EvaluateMapInputs& inputs, const std::filesystem::path& out_dir,
                              const EvaluateMapParams& params);

}  // namespace mapfuse::stages
