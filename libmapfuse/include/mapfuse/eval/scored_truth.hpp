#pragma once
/// @file The truth an `evaluate map` run scores against: the truth map clipped to what the drives
/// could see (the coverage wedge around the true trajectories, docs/evaluate.md), and the
/// trajectory of an aligned LSM against its drive's true trajectory.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "mapfuse/core/vector_map.hpp"
#include "mapfuse/eval/map_metrics.hpp"
#include "mapfuse/eval/trajectory_metrics.hpp"

namespace mapfuse::eval {

/// The truth split into the scored part and the part outside the drives' view.
struct ScoredTruth {
  VectorMap scored;                       ///< truth near the true trajectories (or all of it)
  VectorMap unscored;                     ///< truth outside the drives' view (not scored)
  std::size_t coverage_trajectories = 0;  ///< true trajectories the truth was clipped to
};

/// @brief Clips `truth` to the coverage wedge around every `<drive>.trajectory.json` of
/// `truth_trajectories` (name order); no clipping when the folder is empty or the wedge's
/// lateral size is 0. `truth_name` names the truth in errors.
/// @throws InputError when a trajectory's origin differs from the truth's.
ScoredTruth scoredTruth(VectorMap truth, const std::string& truth_name,
                        const std::filesystem::path& truth_trajectories,
                        const CoverageWedge& coverage);

/// @brief Fewest drives that must observe a true element for `observedTruth` to keep it:
/// aggregate's DBSCAN MinPts, what a crowd map can confirm (aggregate/settings.hpp).
int observedMinDrives();

/// @brief `truth` split by what the simulated drives `lsm_files` observed (their elements'
/// truth ids): `scored` the scored true elements at least observedMinDrives() drives observed,
/// `unscored` the rest. It separates what the crowd saw too rarely from what aggregation lost
/// (issue 36). nullopt when the LSMs carry no truth ids. Reads each LSM once.
std::optional<ScoredTruth> observedTruth(const ScoredTruth& truth,
                                         const std::vector<std::string>& lsm_files);

/// @brief evaluateMap of `map` against truth.scored (truth.unscored out of scope) and, with
/// `observed`, per discrete class the completeness over its scored elements
/// (completeness_observed, truth_observed).
MapMetrics scoreMap(const VectorMap& map, const ScoredTruth& truth,
                    const std::optional<ScoredTruth>& observed, const MapEvalParams& p);

/// @brief Trajectory metrics of the aligned LSM `lsm_file` against
/// `<truth_trajectories>/<drive_id>.trajectory.json`.
/// @throws IoError when that true trajectory does not exist.
TrajectoryMetrics compareLsmToTruth(const std::string& lsm_file,
                                    const std::filesystem::path& truth_trajectories,
                                    const TrajectoryEvalSettings& settings);

}  // namespace mapfuse::eval
