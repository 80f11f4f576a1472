#include "mapfuse/eval/change_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <tuple>
#include <unordered_map>

#include "mapfuse/core/error.hpp"

namespace mapfuse::eval {
namespace {

constexpr double kOriginDegrees = 1e-7;   // about 1 cm
constexpr double kOriginAltitude = 1e-3;  // m

std::optional<double> ratio(int num, int den) {
  if (den == 0) return std::nullopt;
  return double(num) / double(den);
}

UnmatchedChange describe(const MapChange& c) {
  UnmatchedChange u{c.kind, c.cls, std::nullopt, std::nullopt};
  if (c.before) u.before_id = c.before->id;
  if (c.after) u.after_id = c.after->id;
  return u;
}

/// Pairs of (detected, true) indices: by kind and before_id, additions by nearest centres.
std::vector<std::pair<std::size_t, std::size_t>> matchChanges(const MapChanges& detected,
                                                              const MapChanges& truth,
                                                              double added_distance) {
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  std::map<std::pair<ChangeKind, int64_t>, std::size_t> true_by_id;
  for (std::size_t t = 0; t < truth.changes.size(); ++t)
    if (truth.changes[t].before)
      true_by_id[{truth.changes[t].kind, truth.changes[t].before->id}] = t;
  struct Candidate {
    double distance;
    std::size_t d, t;
  };
  std::vector<Candidate> additions;
  for (std::size_t d = 0; d < detected.changes.size(); ++d) {
    const MapChange& c = detected.changes[d];
    if (c.kind != ChangeKind::kAdded) {
      const auto it = true_by_id.find({c.kind, c.before->id});
      if (it != true_by_id.end()) pairs.emplace_back(d, it->second);
      continue;
    }
    const Eigen::Vector3d centre = instanceCentre(*c.after);
    for (std::size_t t = 0; t < truth.changes.size(); ++t) {
      const MapChange& tc = truth.changes[t];
      if (tc.kind != ChangeKind::kAdded || tc.cls != c.cls) continue;
      const double dist = (instanceCentre(*tc.after) - centre).head<2>().norm();
      if (dist <= added_distance) additions.push_back({dist, d, t});
    }
  }
  std::sort(additions.begin(), additions.end(), [](const Candidate& a, const Candidate& b) {
    return std::tie(a.distance, a.d, a.t) < std::tie(b.distance, b.d, b.t);
  });
  std::set<std::size_t> used_d, used_t;
  for (const auto& a : additions)
    if (!used_d.count(a.d) && !used_t.count(a.t)) {
      used_d.insert(a.d), used_t.insert(a.t);
      pairs.emplace_back(a.d, a.t);
    }
  return pairs;
}

/// Adds one change's outcome to the overall, kind and class counts.
void count(ChangeScores& s, const MapChange& c, int ChangeCounts::*field) {
  ++(s.overall.*field);
  ++(s.by_kind[c.kind].*field);
  ++(s.by_class[c.cls].*field);
}

}  // namespace

std::optional<double> ChangeCounts::precision() const {
  return ratio(tp, tp + fp);
}
std::optional<double> ChangeCounts::recall() const {
  return ratio(tp, tp + fn);
}
std::optional<double> ChangeCounts::f1() const {
  return ratio(2 * tp, 2 * tp + fp + fn);
}

std::optional<double> ChangeScores::falseRemovalRate() const {
  return ratio(false_removals, unchanged_elements);
}

void checkAgainstBefore(const MapChanges& changes, const std::string& file, const VectorMap& before,
                        const std::string& before_file) {
  const geo::GeoOrigin &a = changes.origin, &b = before.origin;
  if (std::abs(a.lat - b.lat) > kOriginDegrees || std::abs(a.lon - b.lon) > kOriginDegrees ||
      std::abs(a.alt - b.alt) > kOriginAltitude)
    throw InputError(file + ": origin differs from the before map's (" + before_file +
                     "): the changes describe another map");
  std::unordered_map<int64_t, CrowdClass> classes;
  for (const auto& m : before.instances) classes[m.id] = m.cls;
  for (std::size_t i = 0; i < changes.changes.size(); ++i) {
    const MapChange& c = changes.changes[i];
    if (!c.before) continue;
    const std::string field = "changes[" + std::to_string(i) + "].before_id";
    const auto it = classes.find(c.before->id);
    if (it == classes.end())
      throw ParseError(
          file, field,
          std::to_string(c.before->id) + " is not an element of the before map " + before_file);
    if (it->second != c.cls)
      throw ParseError(file, field,
                       std::to_string(c.before->id) + " is a " + crowdClassName(it->second) +
                           " in the before map " + before_file + ", not a " +
                           crowdClassName(c.cls));
  }
}

ChangeScores scoreChanges(const MapChanges& detected, const MapChanges& truth,
                          const VectorMap& before, const ChangeScoreSettings& settings) {
  ChangeScores s;
  for (int k = 0; k < kNumChangeKinds; ++k) s.by_kind[ChangeKind(k)];
  for (int c = 0; c < kNumCrowdClasses; ++c) s.by_class[CrowdClass(c)];
  const auto pairs = matchChanges(detected, truth, settings.added_match_distance);
  std::vector<bool> d_matched(detected.changes.size()), t_matched(truth.changes.size());
  for (const auto& [d, t] : pairs) d_matched[d] = t_matched[t] = true;
  for (std::size_t t = 0; t < truth.changes.size(); ++t) {
    count(s, truth.changes[t], t_matched[t] ? &ChangeCounts::tp : &ChangeCounts::fn);
    if (!t_matched[t]) s.missed.push_back(describe(truth.changes[t]));
  }
  std::set<int64_t> touched;  // before ids of true changes
  for (const auto& c : truth.changes)
    if (c.before) touched.insert(c.before->id);
  for (const auto& m : before.instances) s.unchanged_elements += touched.count(m.id) ? 0 : 1;
  for (std::size_t d = 0; d < detected.changes.size(); ++d) {
    if (d_matched[d]) continue;
    const MapChange& c = detected.changes[d];
    count(s, c, &ChangeCounts::fp);
    s.wrong.push_back(describe(c));
    if (c.before && !touched.count(c.before->id))
      ++(c.kind == ChangeKind::kRemoved ? s.false_removals : s.false_other);
  }
  return s;
}

}  // namespace mapfuse::eval
