#include "mapfuse/eval/trajectory_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "mapfuse/core/error.hpp"
#include "mapfuse/core/pose_at_stamp.hpp"
#include "mapfuse/geo/origin.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/json_geometry.hpp"
#include "mapfuse/io/json_view.hpp"

namespace mapfuse::eval {

std::vector<std::pair<std::filesystem::path, TrueTrajectory>> readTrueTrajectories(
    const std::filesystem::path& folder) {
  if (!std::filesystem::is_directory(folder))
    throw IoError(folder.string(), "not a folder of <drive>.trajectory.json files");
  std::vector<std::filesystem::path> paths;
  for (const auto& e : std::filesystem::directory_iterator(folder)) {
    const std::string name = e.path().filename().string();
    if (name.size() > 16 && name.rfind(".trajectory.json") == name.size() - 16)
      paths.push_back(e.path());
  }
  std::sort(paths.begin(), paths.end());
  std::vector<std::pair<std::filesystem::path, TrueTrajectory>> out;
  for (const auto& f : paths) out.emplace_back(f, readTrueTrajectory(f));
  return out;
}

TrueTrajectory readTrueTrajectory(const std::filesystem::path& path) {
  const auto doc = io::readDocument(path);
  const io::JsonView v(doc, path.string());
  v.checkFormat("mapfuse.trajectory", 1);
  TrueTrajectory t;
  t.drive_id = v.at("drive_id").string();
  if (v.at("frame").string() != "enu") v.at("frame").fail("a true trajectory must be in 'enu'");
  t.origin = io::readOrigin(v.at("origin"));
  const auto poses = v.at("poses");
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const auto p = poses.at(i);
    t.poses.push_back({p.at("id").integer(), p.at("stamp").number(), io::readPose(p.at("pose"))});
  }
  return t;
}

namespace {
double angleDeg(const Eigen::Matrix3d& R) {
  return Eigen::AngleAxisd(R).angle() * 180.0 / M_PI;
}

constexpr double kSameStamp = 1e-6;  // s: stamps this close are the same instant
}  // namespace

std::vector<const TruePose*> sortedByStamp(const TrueTrajectory& truth) {
  std::vector<const TruePose*> by_stamp;
  for (const auto& p : truth.poses) by_stamp.push_back(&p);
  std::sort(by_stamp.begin(), by_stamp.end(),
            [](const TruePose* a, const TruePose* b) { return a->stamp < b->stamp; });
  return by_stamp;
}

std::optional<Pose3> truePoseAt(const std::vector<const TruePose*>& sorted, double stamp) {
  return poseAtStamp(
      sorted.size(), stamp, [&](std::size_t i) { return sorted[i]->stamp; },
      [&](std::size_t i) { return sorted[i]->T_enu_body; }, kSameStamp);
}

TrajectoryMetrics compareTrajectory(const Lsm& lsm, const TrueTrajectory& truth,
                                    double rpe_distance, const std::string& source) {
  if (lsm.frame != LsmFrame::kEnu || !lsm.origin)
    throw InputError(source +
                     ": trajectory metrics need an LSM in frame 'enu' (georef/align output)");
  // The truth in the LSM's ENU frame (georef may have chosen another origin).
  const bool convert = !geo::sameOrigin(*lsm.origin, truth.origin);
  const geo::EnuConverter from(truth.origin), to(*lsm.origin);
  // Keyframes are matched to the truth by time stamp (ids differ when lsm-build chose its own
  // keyframes from raw frames): the true pose at a stamp, interpolated between its two
  // neighbours when no true pose has that stamp.
  const std::vector<const TruePose*> by_stamp = sortedByStamp(truth);
  std::vector<std::pair<Pose3, Pose3>> pairs;  // (estimate, truth) in keyframe order
  for (const auto& k : lsm.keyframes) {
    const std::optional<Pose3> t = truePoseAt(by_stamp, k.stamp);
    if (!t) continue;
    pairs.emplace_back(k.T_frame_body, convert ? geo::reexpressPose(*t, from, to) : *t);
  }
  if (pairs.empty())
    throw InputError(source + ": no keyframe stamp lies within the true trajectory of drive '" +
                     truth.drive_id + "'");
  TrajectoryMetrics m;
  m.drive_id = lsm.drive_id;
  m.matched = pairs.size();
  std::vector<double> at, ar, rt, rr;
  for (const auto& [e, t] : pairs) {
    at.push_back((e.translation() - t.translation()).norm());
    ar.push_back(angleDeg(t.linear().transpose() * e.linear()));
  }
  // RPE: from each keyframe to the first one at least rpe_distance further along the truth
  std::vector<double> s(pairs.size(), 0.0);
  for (std::size_t i = 1; i < pairs.size(); ++i)
    s[i] = s[i - 1] + (pairs[i].second.translation() - pairs[i - 1].second.translation()).norm();
  std::size_t j = 0;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    j = std::max(j, i);
    while (j < pairs.size() && s[j] - s[i] < rpe_distance) ++j;
    if (j >= pairs.size()) break;
    const Pose3 d_est = pairs[i].first.inverse() * pairs[j].first;
    const Pose3 d_true = pairs[i].second.inverse() * pairs[j].second;
    const Pose3 err = d_true.inverse() * d_est;
    rt.push_back(err.translation().norm());
    rr.push_back(angleDeg(err.linear()));
  }
  m.ate_translation = errorStats(at);
  m.ate_rotation = errorStats(ar);
  m.rpe_translation = errorStats(rt);
  m.rpe_rotation = errorStats(rr);
  return m;
}

nlohmann::json toJson(const TrajectoryMetrics& m) {
  return {{"drive_id", m.drive_id},
          {"matched_keyframes", m.matched},
          {"ate_translation_m", toJson(m.ate_translation)},
          {"ate_rotation_deg", toJson(m.ate_rotation)},
          {"rpe_translation_m", toJson(m.rpe_translation)},
          {"rpe_rotation_deg", toJson(m.rpe_rotation)}};
}

}  // namespace mapfuse::eval
