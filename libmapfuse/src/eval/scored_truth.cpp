#include "mapfuse/eval/scored_truth.hpp"

#include <map>
#include <set>

#include "mapfuse/aggregate/settings.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/geo/origin.hpp"
#include "mapfuse/io/lsm_io.hpp"

namespace mapfuse::eval {

ScoredTruth scoredTruth(VectorMap truth, const std::string& truth_name,
                        const std::filesystem::path& truth_trajectories,
                        const CoverageWedge& coverage) {
  ScoredTruth out;
  out.unscored.origin = truth.origin;
  if (truth_trajectories.empty() || coverage.lateral <= 0) {
    out.scored = std::move(truth);
    return out;
  }
  // score only what the drives could see: truth near the true trajectories, which must share
  // the truth map's origin
  const auto trajectories = readTrueTrajectories(truth_trajectories.string());
  std::vector<Pose3> poses;
  for (const auto& [file, t] : trajectories) {
    if (!geo::sameOrigin(t.origin, truth.origin))
      throw InputError(file.string() + ": origin differs from the truth map " + truth_name);
    for (const auto& p : t.poses) poses.push_back(p.T_enu_body);
  }
  out.coverage_trajectories = trajectories.size();
  out.scored = clipToCoverage(truth, poses, coverage, &out.unscored);
  return out;
}

TrajectoryMetrics compareLsmToTruth(const std::string& lsm_file,
                                    const std::filesystem::path& truth_trajectories,
                                    const TrajectoryEvalSettings& settings) {
  const Lsm lsm = io::readLsm(lsm_file);
  const auto truth_file = truth_trajectories / (lsm.drive_id + ".trajectory.json");
  if (!std::filesystem::exists(truth_file))
    throw IoError(truth_file.string(), "true trajectory of drive '" + lsm.drive_id + "' not found");
  return compareTrajectory(lsm, readTrueTrajectory(truth_file), settings.rpe_distance, lsm_file);
}

int observedMinDrives() {
  return aggregate::DiscreteMergeParams{}.min_pts;
}

std::optional<ScoredTruth> observedTruth(const ScoredTruth& truth,
                                         const std::vector<std::string>& lsm_files) {
  // Drives per (class, true element): one LSM at a time, elements without covariances.
  std::map<std::pair<CrowdClass, int64_t>, std::set<std::string>> drives;
  for (const auto& file : lsm_files) {
    const Lsm lsm = io::readLsmInputs({file}, /*covariances=*/false).front();
    for (const auto& e : lsm.elements)
      if (e.truth_id >= 0) drives[{e.cls, e.truth_id}].insert(lsm.drive_id);
  }
  if (drives.empty()) return std::nullopt;
  ScoredTruth out{truth.scored, truth.unscored, truth.coverage_trajectories};
  out.scored.instances.clear();
  for (const auto& t : truth.scored.instances) {
    const auto it = drives.find({t.cls, t.id});
    const bool seen = it != drives.end() && int(it->second.size()) >= observedMinDrives();
    (seen ? out.scored : out.unscored).instances.push_back(t);
  }
  return out;
}

MapMetrics scoreMap(const VectorMap& map, const ScoredTruth& truth,
                    const std::optional<ScoredTruth>& observed, const MapEvalParams& p) {
  MapMetrics metrics = evaluateMap(map, truth.scored, p, &truth.unscored);
  if (!observed) return metrics;
  const MapMetrics m = evaluateMap(map, observed->scored, p, &observed->unscored);
  for (auto& c : metrics.classes) {
    if (c.by_length) continue;  // a lane line's truth id names the whole line
    for (const auto& o : m.classes)
      if (o.cls == c.cls) {
        c.completeness_observed = o.completeness;
        c.truth_observed = o.truth_count;
      }
  }
  return metrics;
}

}  // namespace mapfuse::eval
