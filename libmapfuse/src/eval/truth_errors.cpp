// Element and trajectory errors of LSMs against the simulator's truth (docs/evaluate.md).
#include "mapfuse/eval/truth_errors.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <unordered_map>

#include "mapfuse/core/error.hpp"
#include "mapfuse/geo/origin.hpp"

namespace mapfuse::eval {

namespace {

struct TrueGeom {
  std::vector<Eigen::Vector2d> pts;
  std::vector<double> arc;  // cumulative arc length (lines)
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  bool line = false;       // lane or stop line: offsets to the polyline, not to the centroid
  bool long_line = false;  // line longer than a piece: grouped per piece
};

// Nearest point on a polyline: returns foot point and its arc length.
void nearestOnPolyline(const TrueGeom& g, const Eigen::Vector2d& p, Eigen::Vector2d* foot,
                       double* s) {
  double best = 1e300;
  for (std::size_t i = 0; i + 1 < g.pts.size(); ++i) {
    const Eigen::Vector2d a = g.pts[i], d = g.pts[i + 1] - a;
    const double len2 = d.squaredNorm();
    const double u = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
    const Eigen::Vector2d f = a + u * d;
    const double dist = (p - f).squaredNorm();
    if (dist < best) {
      best = dist;
      *foot = f;
      *s = g.arc[i] + u * std::sqrt(len2);
    }
  }
}

}  // namespace

ElementTruthErrors elementTruthErrors(const std::vector<Lsm>& lsms, const VectorMap& truth,
                                      double piece_length) {
  ElementTruthErrors r;
  if (lsms.empty()) return r;
  for (const auto& l : lsms)
    if (l.frame != LsmFrame::kEnu || !l.origin)
      throw InputError("elementTruthErrors: LSM '" + l.drive_id + "' is not in enu");
  const geo::GeoOrigin& o = *lsms.front().origin;
  const bool convert = !geo::sameOrigin(o, truth.origin);
  const geo::EnuConverter from(truth.origin), to(o);

  std::unordered_map<int64_t, TrueGeom> geom;
  for (const auto& inst : truth.instances) {
    TrueGeom g;
    for (const auto& p : inst.points) {
      const Eigen::Vector3d q = convert ? to.toEnu(from.toWgs84(p)) : p;
      g.pts.push_back(q.head<2>());
      g.centroid += q.head<2>();
    }
    if (g.pts.empty()) continue;
    g.centroid /= double(g.pts.size());
    g.arc.assign(g.pts.size(), 0.0);
    for (std::size_t i = 1; i < g.pts.size(); ++i)
      g.arc[i] = g.arc[i - 1] + (g.pts[i] - g.pts[i - 1]).norm();
    g.line = (inst.cls == CrowdClass::kLaneLine || inst.cls == CrowdClass::kStopLine) &&
             g.pts.size() >= 2;
    g.long_line = g.line && inst.cls == CrowdClass::kLaneLine && g.arc.back() > piece_length;
    geom[inst.id] = std::move(g);
  }

  // group key (truth id, piece) -> drive -> offsets
  std::map<std::pair<int64_t, int>, std::map<int, std::vector<Eigen::Vector2d>>> groups;
  Eigen::Vector2d offset_sum = Eigen::Vector2d::Zero();
  double abs_sum = 0.0;
  for (int l = 0; l < int(lsms.size()); ++l)
    for (const Element& e : lsms[l].elements) {
      const auto it = geom.find(e.truth_id);
      if (e.truth_id < 0 || it == geom.end() || e.points_body.empty()) continue;
      const TrueGeom& g = it->second;
      const auto pts = lsms[l].pointsInFrame(e);
      Eigen::Vector2d off = Eigen::Vector2d::Zero();
      int piece = 0;
      if (g.line) {  // an observation may show part of the line: compare with the line itself
        double s_sum = 0;
        for (const auto& p : pts) {
          Eigen::Vector2d foot = p.head<2>();
          double s = 0;
          nearestOnPolyline(g, p.head<2>(), &foot, &s);
          off += p.head<2>() - foot;
          s_sum += s;
        }
        off /= double(pts.size());
        if (g.long_line) piece = int(std::floor(s_sum / double(pts.size()) / piece_length));
      } else {
        Eigen::Vector2d c = Eigen::Vector2d::Zero();
        for (const auto& p : pts) c += p.head<2>();
        off = c / double(pts.size()) - g.centroid;
      }
      groups[{e.truth_id, piece}][l].push_back(off);
      offset_sum += off;
      abs_sum += off.norm();
      ++r.observations;
    }
  if (r.observations == 0) return r;
  r.mean_abs = abs_sum / r.observations;
  r.mean_offset = (offset_sum / r.observations).norm();
  std::vector<double> spreads;
  for (const auto& [key, drives] : groups) {
    if (drives.size() < 2) continue;
    std::vector<Eigen::Vector2d> means;
    for (const auto& [d, offs] : drives) {
      Eigen::Vector2d m = Eigen::Vector2d::Zero();
      for (const auto& v : offs) m += v;
      means.push_back(m / double(offs.size()));
    }
    Eigen::Vector2d mu = Eigen::Vector2d::Zero();
    for (const auto& m : means) mu += m;
    mu /= double(means.size());
    double v = 0;
    for (const auto& m : means) v += (m - mu).squaredNorm();
    spreads.push_back(std::sqrt(v / double(means.size())));
  }
  r.groups = int(spreads.size());
  if (!spreads.empty()) {
    double s = 0;
    for (double v : spreads) s += v;
    r.spread = s / double(spreads.size());
    std::nth_element(spreads.begin(), spreads.begin() + spreads.size() / 2, spreads.end());
    r.spread_median = spreads[spreads.size() / 2];
  }
  return r;
}

TrajectoryTruthErrors trajectoryTruthErrors(const std::vector<Lsm>& lsms,
                                            const std::map<std::string, TrueTrajectory>& truth) {
  TrajectoryTruthErrors r;
  for (const auto& l : lsms) {
    const auto it = truth.find(l.drive_id);
    if (it == truth.end()) continue;
    if (l.frame != LsmFrame::kEnu || !l.origin)
      throw InputError("trajectoryTruthErrors: LSM '" + l.drive_id + "' is not in enu");
    // True positions in the LSM's ENU frame (georef may have chosen another origin).
    const geo::GeoOrigin& truth_origin = it->second.origin;
    const bool convert = !geo::sameOrigin(*l.origin, truth_origin);
    const geo::EnuConverter from(truth_origin), to(*l.origin);
    // matched by stamp, as evaluate does (lsm-build's keyframe ids are not the simulator's)
    const std::vector<const TruePose*> by_stamp = sortedByStamp(it->second);
    double sq = 0;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    int n = 0;
    for (const auto& k : l.keyframes) {
      const std::optional<Pose3> T = truePoseAt(by_stamp, k.stamp);
      if (!T) continue;
      const Eigen::Vector3d t = T->translation();
      const Eigen::Vector3d d =
          k.T_frame_body.translation() - (convert ? to.toEnu(from.toWgs84(t)) : t);
      sq += d.squaredNorm();
      mean += d;
      ++n;
    }
    if (n == 0) continue;
    const double rms = std::sqrt(sq / n);
    r.ate_mean += rms;
    r.ate_max = std::max(r.ate_max, rms);
    r.bias_mean += (mean / n).head<2>().norm();
    ++r.drives;
  }
  if (r.drives > 0) {
    r.ate_mean /= r.drives;
    r.bias_mean /= r.drives;
  }
  return r;
}

}  // namespace mapfuse::eval
