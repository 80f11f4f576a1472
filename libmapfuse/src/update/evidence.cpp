#include "evidence.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "drive_view.hpp"
#include "mapfuse/aggregate/geometry2d.hpp"
#include "spatial_index.hpp"

namespace mapfuse::update {

Eigen::Vector3d observationCentre(const aggregate::Observation& o) {
  MapInstance m;
  m.cls = o.cls;
  m.points = o.points;
  return instanceCentre(m);
}

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
  return v[v.size() / 2];
}

// Mean horizontal distance from each point of `a` to the nearest point of `b`.
double meanNearest(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b) {
  double sum = 0;
  for (const auto& p : a) {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& q : b) best = std::min(best, (p - q).head<2>().norm());
    sum += best;
  }
  return a.empty() ? 0.0 : sum / double(a.size());
}

// One in-view sample of a lane line: the signed sideways offset of the nearest observed line
// (left of the mapped direction positive) and whether that observation is dashed.
struct LineSample {
  int index = 0;
  double offset = 0;
  bool dashed = false;
};

// The nearest roughly parallel observed segment beside `p` (tangent `t`), within line_search.
bool nearestBeside(const Eigen::Vector3d& p, const Eigen::Vector2d& t, const SegmentIndex& lines,
                   double search, LineSample* out) {
  const Eigen::Vector2d n(-t.y(), t.x());
  double best = search;
  bool found = false;
  lines.visit(p, [&](const SegmentIndex::Segment& sg) {
    const Eigen::Vector2d d = sg.b - sg.a;
    const double len = d.norm();
    if (len < 1e-6 || std::abs(d.dot(t)) < 0.9 * len) return;  // not parallel
    const double u = (p.head<2>() - sg.a).dot(d) / (len * len);
    if (u < -0.3 / len || u > 1 + 0.3 / len) return;  // p not beside this segment
    const Eigen::Vector2d foot = sg.a + std::clamp(u, 0.0, 1.0) * d;
    const double off = (foot - p.head<2>()).dot(n);
    if (std::abs(off) < best) {
      best = std::abs(off);
      *out = LineSample{0, off, sg.dashed};
      found = true;
    }
  });
  return found;
}

// The longest stretch of samples whose running median offset (5 samples) exceeds min_shift;
// gaps of up to 3 samples without an observation do not break it.
void longestShiftedStretch(const std::vector<LineSample>& samples, const EvidenceSettings& s,
                           double spacing, Evidence* ev) {
  std::vector<double> smooth(samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) {
    std::vector<double> w;
    for (std::size_t j = i >= 2 ? i - 2 : 0; j < std::min(samples.size(), i + 3); ++j)
      w.push_back(samples[j].offset);
    smooth[i] = median(w);
  }
  std::size_t best_from = 0, best_to = 0;
  double best_len = 0;
  for (std::size_t i = 0; i < samples.size();) {
    if (std::abs(smooth[i]) <= s.restripe_min_shift) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j + 1 < samples.size() && std::abs(smooth[j + 1]) > s.restripe_min_shift &&
           samples[j + 1].index - samples[j].index <= 3 && smooth[j + 1] * smooth[i] > 0)
      ++j;
    const double len = double(samples[j].index - samples[i].index + 1) * spacing;
    if (len > best_len) best_len = len, best_from = i, best_to = j;
    i = j + 1;
  }
  if (best_len < s.restripe_min_length) return;
  std::vector<double> offs;
  for (std::size_t i = best_from; i <= best_to; ++i) offs.push_back(samples[i].offset);
  ev->shifted = true;
  ev->shift = median(offs);
  ev->shift_from = samples[best_from].index * spacing;
  ev->shift_to = samples[best_to].index * spacing;
}

}  // namespace

double assignmentDistance(const MapInstance& element, const aggregate::Observation& o) {
  const Eigen::Vector3d c = observationCentre(o);
  if (element.cls == CrowdClass::kStopLine)
    return aggregate::distanceToPolyline2d(c, element.points);
  return (c - instanceCentre(element)).head<2>().norm();
}

std::vector<Eigen::Vector3d> turnedRound(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d lo = points.front(), hi = points.front();
  for (const auto& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const Eigen::Vector3d c = 0.5 * (lo + hi);
  std::vector<Eigen::Vector3d> out;
  for (const auto& p : points) out.emplace_back(2 * c.x() - p.x(), 2 * c.y() - p.y(), p.z());
  return out;
}

Evidence discreteEvidence(const MapInstance& element, const DriveObservations& assigned, int drive,
                          const EvidenceSettings& s) {
  Evidence ev;
  ev.drive = drive;
  const aggregate::Observation* nearest = nullptr;
  double best = std::numeric_limits<double>::infinity();
  for (const auto* o : assigned) {
    const double d = assignmentDistance(element, *o);
    if (d < best) best = d, nearest = o;
  }
  if (!nearest) return ev;
  ev.present = true;
  ev.displacement = (observationCentre(*nearest) - instanceCentre(element)).head<2>();
  if (element.cls == CrowdClass::kGroundArrow && element.points.size() >= 3) {
    const double same = meanNearest(nearest->points, element.points);
    const double turned = meanNearest(nearest->points, turnedRound(element.points));
    ev.other_type = turned + s.retype_margin < same;
  }
  return ev;
}

Evidence laneLineEvidence(const MapInstance& line,
                          const std::vector<const MapInstance*>& neighbours,
                          const SegmentIndex& lines, const DriveView& view, int drive,
                          const UpdateSettings& s, bool* in_view, bool* has_data) {
  Evidence ev;
  ev.drive = drive;
  *in_view = *has_data = false;
  const double spacing = s.view.sample_spacing;
  const auto samples = aggregate::resamplePolyline(line.points, spacing);
  std::vector<LineSample> seen;
  int dashed = 0, solid = 0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (!view.sees(samples[i])) continue;
    *in_view = true;
    const std::size_t a = i > 0 ? i - 1 : i, b = std::min(samples.size() - 1, i + 1);
    Eigen::Vector2d t = (samples[b] - samples[a]).head<2>();
    if (t.norm() < 1e-9) continue;
    t.normalize();
    LineSample ls;
    if (!nearestBeside(samples[i], t, lines, s.evidence.line_search, &ls)) continue;
    const Eigen::Vector3d normal(-t.y(), t.x(), 0.0);
    const Eigen::Vector3d seen_at = samples[i] + ls.offset * normal;  // the observed line
    // An observed line nearer to a neighbouring map line than to this one is the neighbour's
    // paint, unless the neighbour has paint of its own nearer to it there (then this is a second
    // line beside it: this one, moved next to it).
    const double noise = 2.0 * s.evidence.restripe_min_shift;
    bool theirs = false;
    for (const MapInstance* n : neighbours) {
      const double dn = aggregate::distanceToPolyline2d(seen_at, n->points);
      if (dn >= std::abs(ls.offset)) continue;
      if (dn < noise) {
        theirs = true;
        break;
      }
      const Eigen::Vector3d a = seen_at + dn * normal, b = seen_at - dn * normal;
      const Eigen::Vector3d foot = aggregate::distanceToPolyline2d(a, n->points) <
                                           aggregate::distanceToPolyline2d(b, n->points)
                                       ? a
                                       : b;
      // the neighbour's own paint near the foot, up to 6 m along (a dashed neighbour's gaps)
      LineSample own;
      bool has_own = false;
      for (const double along : {0.0, -3.0, 3.0, -6.0, 6.0}) {
        const Eigen::Vector3d q = foot + along * Eigen::Vector3d(t.x(), t.y(), 0.0);
        if (nearestBeside(q, t, lines, dn - noise, &own)) {
          has_own = true;
          break;
        }
      }
      if (!has_own) {
        theirs = true;
        break;
      }
    }
    if (theirs) continue;
    ls.index = int(i);
    seen.push_back(ls);
    if (std::abs(ls.offset) <= s.evidence.restripe_min_shift) (ls.dashed ? dashed : solid)++;
  }
  if (seen.empty()) return ev;
  *has_data = true;
  ev.present = true;
  for (const LineSample& ls : seen) ev.offsets.emplace_back(ls.index, ls.offset);
  longestShiftedStretch(seen, s.evidence, spacing, &ev);
  const bool mapped_dashed = line.attributes.style == LineStyle::kDashed;
  const int agree = mapped_dashed ? dashed : solid, disagree = mapped_dashed ? solid : dashed;
  ev.other_type = !ev.shifted && disagree > agree && disagree >= 3;
  return ev;
}

}  // namespace mapfuse::update
