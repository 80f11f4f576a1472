#include "mapfuse/update/change_detection.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "drive_view.hpp"
#include "evidence.hpp"
#include "mapfuse/aggregate/dbscan.hpp"
#include "mapfuse/aggregate/geometry2d.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/geo/origin.hpp"
#include "spatial_index.hpp"

namespace mapfuse::update {
namespace {

using aggregate::Observation;

double medianOf(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
  return v[v.size() / 2];
}

double logit(double p) {
  return std::log(p / (1 - p));
}

bool movable(CrowdClass c) {
  return c == CrowdClass::kPole || c == CrowdClass::kTrafficSign || c == CrowdClass::kTrafficLight;
}

// The new drives' confident observations; per observation of a discrete class the map element
// of its class nearest to it within move_max (-1: none, a candidate addition).
struct Assignment {
  aggregate::ObservationSet set;
  std::vector<int> element;                                 ///< per observation
  std::vector<std::vector<DriveObservations>> per_element;  ///< [element][drive]
  std::vector<DriveObservations> lines;                     ///< lane lines per drive
  std::vector<SegmentIndex> line_index;                     ///< their segments, per drive
};

void assign(const VectorMap& map, std::size_t drives, const EvidenceSettings& s, Assignment& a) {
  a.element.assign(a.set.items.size(), -1);
  a.per_element.assign(map.instances.size(), std::vector<DriveObservations>(drives));
  a.lines.assign(drives, {});
  const ElementIndex index(map, s.move_max);  // the candidates within move_max of a point
  for (std::size_t i = 0; i < a.set.items.size(); ++i) {
    const Observation& o = a.set.items[i];
    if (o.confidence < s.min_confidence) continue;
    if (o.cls == CrowdClass::kLaneLine) {
      a.lines[o.drive].push_back(&o);
      continue;
    }
    double best = s.move_max;
    for (const std::size_t e : index.near(observationCentre(o))) {
      if (map.instances[e].cls != o.cls) continue;
      const double d = assignmentDistance(map.instances[e], o);
      if (d < best) best = d, a.element[i] = int(e);
    }
    if (a.element[i] >= 0) a.per_element[a.element[i]][o.drive].push_back(&o);
  }
  for (const auto& lines : a.lines) a.line_index.emplace_back(lines, s.line_search);
}

Assignment assignObservations(const VectorMap& map, const std::vector<Lsm>& lsms,
                              const std::vector<std::string>& sources, const EvidenceSettings& s) {
  Assignment a;
  a.set = aggregate::collectObservations(lsms, sources);
  if (!geo::sameOrigin(a.set.origin, map.origin))
    throw InputError(sources[0] +
                     ": origin differs from the map's; the new drives must be in "
                     "the map's ENU frame (georef --origin of the map)");
  assign(map, lsms.size(), s, a);
  return a;
}

std::vector<std::string> driveIds(const std::vector<Evidence>& evs, const std::vector<Lsm>& lsms) {
  std::vector<std::string> ids;
  for (const auto& e : evs) ids.push_back(lsms[e.drive].drive_id);
  return ids;
}

// Per map element the probability that a drive passing it observes it, from the map's own
// history (docs/update.md "Accumulation"): of the drives that passed its place (the largest
// support of the map's elements within support_radius: the lane lines there, which every
// passing drive sees), the share that observed it, (drives + 1) / (passed + 2), at most
// max_detection_probability. An element few of its passing drives saw (a sign seen from behind, a
// stop line of a crossing road) is weak evidence when missed. Without support (a map not made
// by aggregate): detection_probability.
std::vector<double> detectionProbabilities(const VectorMap& map, const DecisionSettings& d) {
  const ElementIndex index(map, d.support_radius);  // every element within reach of a point
  std::vector<Eigen::Vector3d> centre(map.instances.size());
  for (std::size_t e = 0; e < map.instances.size(); ++e)
    centre[e] = instanceCentre(map.instances[e]);
  std::vector<double> pd(map.instances.size(), d.detection_probability);
  for (std::size_t e = 0; e < map.instances.size(); ++e) {
    const int own = map.instances[e].support.drives;
    if (own <= 0) continue;
    int passed = own;
    for (const std::size_t o : index.near(centre[e]))
      if ((centre[o] - centre[e]).head<2>().norm() <= d.support_radius)
        passed = std::max(passed, map.instances[o].support.drives);
    pd[e] = std::min(d.max_detection_probability, double(own + 1) / double(passed + 2));
  }
  return pd;
}

// Removal by log-odds over the traversals that had the element in view: each one that missed
// it adds log((1 - Pfa) / (1 - Pd)), each one that saw it adds log(Pfa / Pd), Pd the element's
// detection probability (detectionProbabilities).
std::optional<MapChange> decideDiscrete(const MapInstance& m, double pd,
                                        const std::vector<Evidence>& present,
                                        const std::vector<Evidence>& missing,
                                        const std::vector<Lsm>& lsms, const UpdateSettings& s) {
  const DecisionSettings& d = s.decision;
  const double pfa = std::min(d.false_alarm_probability, 0.5 * pd);  // a miss stays evidence
  const double l = logit(d.removal_prior) +
                   double(missing.size()) * std::log((1 - pfa) / (1 - pd)) +
                   double(present.size()) * std::log(pfa / pd);
  MapChange c;
  c.cls = m.cls;
  c.before = m;
  if (l > 0) {
    c.kind = ChangeKind::kRemoved;
    c.confidence = 1.0 / (1.0 + std::exp(-l));
    c.supporting_traversals = driveIds(missing, lsms);
    return c;
  }
  if (present.empty()) return std::nullopt;
  std::vector<double> dx, dy;
  std::vector<Evidence> moved, turned;
  for (const auto& e : present) {
    dx.push_back(e.displacement.x());
    dy.push_back(e.displacement.y());
    if (e.displacement.norm() > s.evidence.match_distance) moved.push_back(e);
    if (e.other_type) turned.push_back(e);
  }
  const Eigen::Vector2d shift(medianOf(dx), medianOf(dy));
  c.after = m;
  if (movable(m.cls) && shift.norm() > s.evidence.match_distance) {
    c.kind = ChangeKind::kMoved;
    for (auto& p : c.after->points) p.head<2>() += shift;
    c.confidence = double(moved.size()) / double(present.size());
    c.supporting_traversals = driveIds(moved, lsms);
    return c;
  }
  if (2 * turned.size() > present.size()) {
    c.kind = ChangeKind::kRetyped;
    c.after->points = turnedRound(m.points);
    c.confidence = double(turned.size()) / double(present.size());
    c.supporting_traversals = driveIds(turned, lsms);
    return c;
  }
  return std::nullopt;
}

// The re-striped line from what the traversals saw: the line's samples (every `spacing` m, as
// the evidence indexes them) within the shifted stretch grown by `grow` m at each end, each
// moved sideways by the median offset the shifting traversals observed there (running median
// of 5 samples; samples no traversal saw take the nearest seen one's); outside the stretch the
// mapped points as they were. A ramp where the paint moves over comes out as observed.
std::vector<Eigen::Vector3d> restripedLine(const std::vector<Eigen::Vector3d>& pts,
                                           const std::vector<Evidence>& shifted, double spacing,
                                           double from, double to, double grow) {
  const auto samples = aggregate::resamplePolyline(pts, spacing);
  const int n = int(samples.size());
  std::vector<std::vector<double>> seen(static_cast<std::size_t>(n));
  for (const auto& e : shifted)
    for (const auto& [i, off] : e.offsets)
      if (i >= 0 && i < n) seen[std::size_t(i)].push_back(off);
  const int a = std::max(0, int(std::floor((from - grow) / spacing)));
  const int b = std::min(n - 1, int(std::ceil((to + grow) / spacing)));
  std::vector<double> off(static_cast<std::size_t>(n), 0.0);
  std::vector<char> known(static_cast<std::size_t>(n), 0);
  for (int i = a; i <= b; ++i)
    if (!seen[std::size_t(i)].empty()) off[i] = medianOf(seen[i]), known[i] = 1;
  for (int i = a; i <= b; ++i) {  // unseen samples: the nearest seen one's offset
    if (known[i]) continue;
    for (int d = 1; d <= b - a; ++d) {
      if (i - d >= a && known[i - d]) {
        off[i] = off[i - d];
        break;
      }
      if (i + d <= b && known[i + d]) {
        off[i] = off[i + d];
        break;
      }
    }
  }
  std::vector<double> smooth = off;
  for (int i = a; i <= b; ++i) {
    std::vector<double> w;
    for (int j = std::max(a, i - 2); j <= std::min(b, i + 2); ++j) w.push_back(off[j]);
    smooth[i] = medianOf(w);
  }
  std::vector<double> along(pts.size(), 0.0);  // arc length of each mapped point
  for (std::size_t k = 1; k < pts.size(); ++k)
    along[k] = along[k - 1] + (pts[k] - pts[k - 1]).head<2>().norm();
  std::vector<Eigen::Vector3d> out;
  for (std::size_t k = 0; k < pts.size(); ++k)  // the mapped points before the stretch
    if (along[k] < (a - 0.5) * spacing) out.push_back(pts[k]);
  for (int i = a; i <= b; ++i) {
    const int j0 = std::max(0, i - 1), j1 = std::min(n - 1, i + 1);
    Eigen::Vector2d t = (samples[j1] - samples[j0]).head<2>();
    if (t.norm() < 1e-9) continue;
    t.normalize();
    Eigen::Vector3d q = samples[i];
    q.head<2>() += smooth[i] * Eigen::Vector2d(-t.y(), t.x());
    out.push_back(q);
  }
  for (std::size_t k = 0; k < pts.size(); ++k)  // and after it
    if (along[k] > (b + 0.5) * spacing) out.push_back(pts[k]);
  return out;
}

std::optional<MapChange> decideLine(const MapInstance& m, const std::vector<Evidence>& seen,
                                    const std::vector<Lsm>& lsms, double spacing,
                                    double restripe_grow) {
  std::vector<Evidence> shifted, retyped;
  for (const auto& e : seen) {
    if (e.shifted) shifted.push_back(e);
    if (e.other_type) retyped.push_back(e);
  }
  MapChange c;
  c.cls = m.cls;
  c.before = c.after = m;
  if (2 * shifted.size() > seen.size()) {
    std::vector<double> from, to;
    for (const auto& e : shifted) from.push_back(e.shift_from), to.push_back(e.shift_to);
    c.kind = ChangeKind::kRestriped;
    c.after->points =
        restripedLine(m.points, shifted, spacing, medianOf(from), medianOf(to), restripe_grow);
    c.after->bezier.clear();
    c.confidence = double(shifted.size()) / double(seen.size());
    c.supporting_traversals = driveIds(shifted, lsms);
    return c;
  }
  if (2 * retyped.size() > seen.size()) {
    c.kind = ChangeKind::kRetyped;
    const bool dashed = m.attributes.style == LineStyle::kDashed;
    c.after->attributes.style = dashed ? LineStyle::kSolid : LineStyle::kDashed;
    c.confidence = double(retyped.size()) / double(seen.size());
    c.supporting_traversals = driveIds(retyped, lsms);
    return c;
  }
  return std::nullopt;
}

// Per lane line the map's other lane lines whose bounding box comes within `reach` of its own
// (`only`: the lines to do it for; the others get none).
std::vector<std::vector<const MapInstance*>> laneLineNeighbours(const VectorMap& map, double reach,
                                                                const std::vector<char>& only) {
  const std::size_t n = map.instances.size();
  std::vector<Eigen::Vector2d> lo(n), hi(n);
  for (std::size_t i = 0; i < n; ++i) {
    lo[i] = hi[i] = map.instances[i].points.front().head<2>();
    for (const auto& p : map.instances[i].points)
      lo[i] = lo[i].cwiseMin(p.head<2>()), hi[i] = hi[i].cwiseMax(p.head<2>());
  }
  const ElementIndex index(map, reach);
  std::vector<std::vector<const MapInstance*>> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (!only[i] || map.instances[i].cls != CrowdClass::kLaneLine) continue;
    for (const std::size_t j : index.within(lo[i], hi[i])) {
      if (i == j || map.instances[j].cls != CrowdClass::kLaneLine) continue;
      const bool apart = (lo[j].array() > hi[i].array() + reach).any() ||
                         (hi[j].array() < lo[i].array() - reach).any();
      if (!apart) out[i].push_back(&map.instances[j]);
    }
  }
  return out;
}

// The map elements a new drive may have had in view: those whose box comes within the camera's
// reach of one of its keyframes (the rest are not verified without a look at their evidence).
std::vector<char> nearDrives(const VectorMap& map, const std::vector<Lsm>& lsms,
                             const ViewSettings& v) {
  const double reach = v.camera_x + v.max_range;
  const ElementIndex index(map, 0.0);
  std::vector<char> near(map.instances.size(), 0);
  for (const Lsm& lsm : lsms)
    for (const auto& k : lsm.keyframes) {
      const Eigen::Vector2d c = k.T_frame_body.translation().head<2>();
      for (const std::size_t e : index.within(c.array() - reach, c.array() + reach)) near[e] = 1;
    }
  return near;
}

// Per element: the traversals that had it in view and what each saw; then the decision.
void detectElementChanges(const VectorMap& map, const std::vector<Lsm>& lsms,
                          const std::vector<DriveView>& views, const Assignment& a,
                          const UpdateSettings& s, UpdateResult* out) {
  const std::vector<char> near = nearDrives(map, lsms, s.view);
  const auto neighbours = laneLineNeighbours(map, s.evidence.line_search, near);
  const std::vector<double> pd = detectionProbabilities(map, s.decision);
  for (std::size_t e = 0; e < map.instances.size(); ++e) {
    const MapInstance& m = map.instances[e];
    std::vector<Evidence> present, missing;
    bool any_view = false;
    for (std::size_t d = 0; d < lsms.size() && near[e]; ++d) {
      if (m.cls == CrowdClass::kLaneLine) {
        bool in_view = false, data = false;
        Evidence ev = laneLineEvidence(m, neighbours[e], a.line_index[d], views[d], int(d), s,
                                       &in_view, &data);
        any_view |= in_view;
        if (data) present.push_back(ev);
        continue;
      }
      if (!views[d].sees(instanceCentre(m))) continue;
      any_view = true;
      Evidence ev = discreteEvidence(m, a.per_element[e][d], int(d), s.evidence);
      (ev.present ? present : missing).push_back(ev);
    }
    if (!any_view) {
      out->stats.not_verified.push_back(m.id);
      continue;
    }
    ++out->stats.elements_in_view;
    const auto change =
        m.cls == CrowdClass::kLaneLine
            ? decideLine(m, present, lsms, s.view.sample_spacing, s.evidence.restripe_min_length)
            : decideDiscrete(m, pd[e], present, missing, lsms, s);
    if (change)
      out->changes.changes.push_back(*change);
    else if (present.empty())
      ++out->stats.undecided;
    else
      ++out->stats.confirmed;
  }
}

// Observations no element explains, clustered per class (DBSCAN, MinPts 1, eps
// added_cluster_eps); a cluster is an addition when enough traversals saw it and more than half
// of those that had its place in view.
void detectAdditions(const VectorMap& map, const std::vector<Lsm>& lsms,
                     const std::vector<DriveView>& views, const Assignment& a,
                     const UpdateSettings& s, UpdateResult* out) {
  int64_t next_id = 0;
  for (const auto& m : map.instances) next_id = std::max(next_id, m.id);
  for (int c = 0; c < kNumCrowdClasses; ++c) {
    const auto cls = static_cast<CrowdClass>(c);
    if (cls == CrowdClass::kLaneLine) continue;
    std::vector<std::size_t> idx;
    std::vector<Eigen::Vector3d> centres;
    for (std::size_t i = 0; i < a.set.items.size(); ++i) {
      const Observation& o = a.set.items[i];
      if (o.cls != cls || a.element[i] >= 0 || o.confidence < s.evidence.min_confidence) continue;
      MapInstance tmp;
      tmp.cls = cls;
      tmp.points = o.points;
      idx.push_back(i);
      centres.push_back(instanceCentre(tmp));
    }
    const double eps = s.decision.added_cluster_eps;
    const auto clusters = aggregate::dbscan(idx.size(), 1, [&](std::size_t i) {
      std::vector<std::size_t> n;
      for (std::size_t j = 0; j < idx.size(); ++j)
        if (j != i && (centres[j] - centres[i]).head<2>().norm() <= eps) n.push_back(j);
      return n;
    });
    for (int k = 0; k < clusters.num_clusters; ++k) {
      std::vector<std::size_t> members;
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      std::set<int> drives;
      for (std::size_t i = 0; i < idx.size(); ++i)
        if (clusters.labels[i] == k) {
          members.push_back(i);
          mean += centres[i];
          drives.insert(a.set.items[idx[i]].drive);
        }
      mean /= double(members.size());
      int in_view = 0;
      for (const auto& v : views) in_view += v.sees(mean) ? 1 : 0;
      in_view = std::max(in_view, int(drives.size()));
      if (int(drives.size()) < s.decision.added_min_traversals || 2 * int(drives.size()) <= in_view)
        continue;
      std::size_t rep = members.front();
      for (std::size_t i : members)
        if ((centres[i] - mean).norm() < (centres[rep] - mean).norm()) rep = i;
      const Observation& o = a.set.items[idx[rep]];
      MapChange ch;
      ch.kind = ChangeKind::kAdded;
      ch.cls = cls;
      MapInstance after;
      after.id = ++next_id;
      after.cls = cls;
      after.attributes = o.attributes;
      after.points = o.points;
      after.height = o.height;
      after.support = {int(drives.size()), int(members.size())};
      after.note = "added by update";
      ch.after = after;
      ch.confidence = double(drives.size()) / double(in_view);
      for (int d : drives) ch.supporting_traversals.push_back(lsms[d].drive_id);
      out->changes.changes.push_back(ch);
    }
  }
}

}  // namespace

UpdateResult detectChanges(const VectorMap& map, const std::vector<Lsm>& new_drives,
                           const std::vector<std::string>& sources,
                           const UpdateSettings& settings) {
  for (std::size_t d = 0; d < new_drives.size(); ++d)
    if (new_drives[d].frame != LsmFrame::kEnu)
      throw InputError(sources[d] +
                       ": LSM is in frame 'odom'; update needs the new drives in the "
                       "map's ENU frame (georef --origin of the map)");
  for (std::size_t d = 0; d < new_drives.size(); ++d)
    if (!new_drives[d].origin || !geo::sameOrigin(*new_drives[d].origin, map.origin))
      throw InputError(sources[d] +
                       ": origin differs from the map's; the new drives must be in the map's "
                       "ENU frame (georef --origin of the map)");
  UpdateResult out;
  std::vector<Lsm> lsms = new_drives;
  out.stats.stretches = registerToMap(map, lsms, settings.registration);
  out.changes.origin = map.origin;
  out.changes.source = "update";
  const Assignment a = assignObservations(map, lsms, sources, settings.evidence);
  for (const auto& o : a.set.items)
    out.stats.observations_used += o.confidence >= settings.evidence.min_confidence ? 1 : 0;
  std::vector<DriveView> views;
  for (const Lsm& lsm : lsms)
    views.emplace_back(lsm, settings.view, settings.evidence.min_confidence);
  out.stats.traversals = int(lsms.size());
  detectElementChanges(map, lsms, views, a, settings, &out);
  detectAdditions(map, lsms, views, a, settings, &out);
  out.registered = std::move(lsms);
  return out;
}

}  // namespace mapfuse::update
