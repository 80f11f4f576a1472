#pragma once
/// @file Map quality against ground truth, per class (§5, Song et al. 2023; formulas in
/// docs/evaluate.md): matching of map instances to truth instances (lane lines by overlap
/// within a tolerance, discrete elements by distance), relative precision (mean
/// |rd_obs - rd_truth| over relative distances between neighbouring elements of one class),
/// absolute position error (mean, RMS, 3 sigma), completeness and redundancy (by length for
/// lane lines, by count for every other class).
#include <nlohmann/json.hpp>
#include <vector>

#include "mapfuse/core/param.hpp"
#include "mapfuse/core/se3.hpp"
#include "mapfuse/core/vector_map.hpp"
#include "mapfuse/eval/error_stats.hpp"

namespace mapfuse::eval {

/// Parameters of evaluateMap, each declared once (mapfuse/core/param.hpp).
struct MapEvalParams {
  double line_tolerance = 1.0;      ///< m, a lane-line sample within this of the other map matches
  double discrete_tolerance = 1.5;  ///< m, largest centre distance of a matched discrete pair
  double sample_step = 0.5;         ///< m, spacing of lane-line samples
  double lane_width_min = 2.0;      ///< m, neighbouring lines closer than this are not lanes
  double lane_width_max = 6.0;      ///< m, ... farther than this neither
  double neighbour_max_distance = 100.0;  ///< m, discrete neighbours farther apart are ignored

  template <class V>
  void visit(V& v) {
    using namespace param;
    // the search radii (tolerances, lane_width_max) bound the candidates of each sample
    v("line_tolerance", line_tolerance, "m", "lane-line samples within this distance match",
      gt(0) & le(100));
    v("discrete_tolerance", discrete_tolerance, "m",
      "largest centre distance of a matched discrete element", gt(0) & le(100));
    // lines are sampled every sample_step (1e-7 m: 1e7 samples per metre, out of memory)
    v("sample_step", sample_step, "m", "spacing of lane-line samples (stations)", in(0.01, 100));
    v("lane_width_min", lane_width_min, "m", "neighbouring lines closer than this are not a lane",
      in(0, 100));
    v("lane_width_max", lane_width_max, "m", "neighbouring lines farther than this are not a lane",
      gt(0) & le(100));
    v.relation("lane_width_max", lane_width_max, lane_width_max > lane_width_min,
               "> lane_width_min");
    v("neighbour_max_distance", neighbour_max_distance, "m",
      "discrete elements farther apart are not neighbours", gt(0));
  }
};

struct ClassMetrics {
  CrowdClass cls = CrowdClass::kLaneLine;
  bool by_length = false;  ///< lane lines: completeness/redundancy by length
  std::size_t truth_count = 0, map_count = 0;
  std::size_t matched_truth = 0, matched_map = 0;  ///< instances with a match
  double truth_length = 0, map_length = 0;         ///< m (lane lines)
  double covered_truth_length = 0;                 ///< m of truth within tolerance of the map
  double matched_map_length = 0;                   ///< m of map within tolerance of the truth
  double completeness = 0, redundancy = 0;
  ErrorStats absolute;  ///< position error of matched map geometry, m
  ErrorStats relative;  ///< |rd_obs - rd_truth| over neighbour pairs, m
  /// Discrete classes, simulated drives (`--lsm` whose elements carry truth ids): completeness
  /// over the true elements at least observedMinDrives() drives observed (scored_truth.hpp;
  /// < 0: not computed).
  double completeness_observed = -1;
  std::size_t truth_observed = 0;  ///< those true elements
};

struct MapMetrics {
  std::vector<ClassMetrics> classes;  ///< classes present in the truth or the map, enum order
};

/// @brief The map with its points re-expressed in ENU of `origin` (unchanged when it is the map's).
VectorMap inOrigin(const VectorMap& map, const geo::GeoOrigin& origin);

/// @brief Compares `map` with `truth` (map coordinates are converted to the truth's ENU when the
/// origins differ). With `unscored`, the true elements left out of the score (clipToCoverage's
/// `outside`, in the truth's ENU): map elements (lane-line samples) that match no scored truth
/// but lie within the tolerance of an unscored one are neither credited nor counted redundant.
MapMetrics evaluateMap(const VectorMap& map, const VectorMap& truth, const MapEvalParams& params,
                       const VectorMap* unscored = nullptr);

/// What a forward camera at a pose sees of the ground: body x in [apex_x, range], |y| <= lateral
/// and |y| <= (x - apex_x) tan(half_fov_deg), the apex at the camera.
struct CoverageWedge {
  double lateral = 12.0;       ///< m; 0: `evaluate map` scores the whole truth
  double range = 22.0;         ///< m
  double half_fov_deg = 31.0;  ///< deg; 90: everything ahead
  double apex_x = 1.8;         ///< m, the camera ahead of the body origin (the simulator's mount)

  template <class V>
  void visit(V& v) {
    using namespace param;
    // poses are hashed on a grid of cells hypot(range, lateral): every pose of a drive in one
    // cell when they are huge
    v("coverage_radius", lateral, "m",
      "with --truth-trajectories: score only truth within this distance of a true trajectory "
      "(0 = whole truth)",
      in(0, 1000));
    v("coverage_range", range, "m",
      "with --truth-trajectories: how far ahead of a true pose the truth counts as seen",
      gt(0) & le(1000));
    v("coverage_half_fov_deg", half_fov_deg, "deg",
      "with --truth-trajectories: half opening of the seen wedge ahead of a true pose (the "
      "camera's field of view; 90 = everything ahead)",
      gt(0) & le(90));
    v("coverage_apex_x", apex_x, "m",
      "with --truth-trajectories: the wedge's apex, the camera, this far ahead of the body "
      "origin (the simulator's mount)",
      ge(0) & le(1000));
    v.relation("coverage_apex_x", apex_x, apex_x < range, "< coverage_range");
  }
};

/// @brief The part of a truth map that forward-looking drives could observe: lane lines cut to
/// their pieces (sampled every 0.5 m, pieces shorter than 1 m dropped), other instances kept by
/// their centre, where a point is covered when it lies in the wedge of some pose (what lies
/// behind a drive's start or beside it outside the field of view was never in view).
/// `outside`, when given, receives the rest: instances whose centre is not covered and the
/// uncovered pieces of lane lines.
VectorMap clipToCoverage(const VectorMap& truth, const std::vector<Pose3>& poses,
                         const CoverageWedge& wedge, VectorMap* outside = nullptr);

nlohmann::json toJson(const ClassMetrics& m);
nlohmann::json toJson(const MapMetrics& m);

}  // namespace mapfuse::eval
