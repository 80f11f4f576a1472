#include "mapfuse/eval/map_metrics.hpp"

// Boost.Geometry rtree instantiations trigger GCC false positives.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <algorithm>
#include <boost/geometry.hpp>
#include <boost/geometry/geometries/box.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/index/rtree.hpp>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <unordered_map>

#include "mapfuse/aggregate/geometry2d.hpp"
#include "mapfuse/core/voxel_grid.hpp"
#include "mapfuse/geo/origin.hpp"

namespace mapfuse::eval {
namespace {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;
using Vec3 = Eigen::Vector3d;
using P2 = bg::model::d2::point_xy<double>;
using Box2 = bg::model::box<P2>;
using SegValue = std::pair<Box2, std::pair<int, std::size_t>>;  // (instance, segment)

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Segments of a set of polylines in an rtree: nearest foot queries within a radius.
class SegmentIndex {
 public:
  explicit SegmentIndex(const std::vector<std::vector<Vec3>>& lines) : lines_(lines) {
    std::vector<SegValue> v;
    for (std::size_t i = 0; i < lines.size(); ++i)
      for (std::size_t s = 1; s < lines[i].size(); ++s) {
        const Vec3 &a = lines[i][s - 1], &b = lines[i][s];
        v.push_back({Box2(P2(std::min(a.x(), b.x()), std::min(a.y(), b.y())),
                          P2(std::max(a.x(), b.x()), std::max(a.y(), b.y()))),
                     {int(i), s}});
      }
    tree_ = bgi::rtree<SegValue, bgi::rstar<16>>(v.begin(), v.end());
  }

  /// Visits, per line within `radius` of p, its closest foot point (accept(line, foot, dist)).
  void perLine(const Vec3& p, double radius,
               const std::function<void(int, const Vec3&, double)>& visit) const {
    std::vector<SegValue> hits;
    tree_.query(bgi::intersects(
                    Box2(P2(p.x() - radius, p.y() - radius), P2(p.x() + radius, p.y() + radius))),
                std::back_inserter(hits));
    std::map<int, std::pair<double, Vec3>> best;
    for (const auto& h : hits) {
      const auto [line, s] = h.second;
      Vec3 foot;
      const double d =
          aggregate::distanceToSegment2d(p, lines_[line][s - 1], lines_[line][s], &foot);
      if (d > radius) continue;
      auto it = best.find(line);
      if (it == best.end() || d < it->second.first) best[line] = {d, foot};
    }
    for (const auto& [line, df] : best) visit(line, df.second, df.first);
  }

  /// Closest foot on lines accepted by `filter` within radius; returns distance (inf if none).
  double nearest(const Vec3& p, double radius, Vec3* foot, int* line,
                 const std::function<bool(int)>& filter = {}) const {
    double best = kInf;
    perLine(p, radius, [&](int l, const Vec3& f, double d) {
      if ((filter && !filter(l)) || d >= best) return;
      best = d;
      if (foot) *foot = f;
      if (line) *line = l;
    });
    return best;
  }

 private:
  const std::vector<std::vector<Vec3>>& lines_;
  bgi::rtree<SegValue, bgi::rstar<16>> tree_;
};

ClassMetrics evaluateLines(const std::vector<const MapInstance*>& map,
                           const std::vector<const MapInstance*>& truth,
                           const std::vector<const MapInstance*>& unscored,
                           const MapEvalParams& p) {
  ClassMetrics m;
  m.by_length = true;
  m.truth_count = truth.size();
  m.map_count = map.size();
  std::vector<std::vector<Vec3>> tl, ml, ul;
  for (const auto* t : truth) tl.push_back(t->points);
  for (const auto* i : map) ml.push_back(i->points);
  for (const auto* u : unscored) ul.push_back(u->points);
  const SegmentIndex tindex(tl), mindex(ml), uindex(ul);
  const double tol = p.line_tolerance;

  // map side: matched length, absolute error, which truth line each map line follows
  std::vector<double> abs_errors;
  std::vector<int> follows(ml.size(), -1);
  for (std::size_t i = 0; i < ml.size(); ++i) {
    const auto s = aggregate::resamplePolyline(ml[i], p.sample_step);
    std::map<int, double> votes;
    double matched = 0, length = 0, out_of_scope = 0;
    for (std::size_t k = 1; k < s.size(); ++k) {
      const Vec3 c = 0.5 * (s[k - 1] + s[k]);
      const double len = (s[k] - s[k - 1]).norm();
      int line = -1;
      const double d = tindex.nearest(c, tol, nullptr, &line);
      if (d > tol && uindex.nearest(c, tol, nullptr, nullptr) <= tol) {
        out_of_scope += len;
        continue;
      }
      length += len;
      if (d <= tol) {
        matched += len;
        votes[line] += len;
        abs_errors.push_back(d);
      }
    }
    m.map_length += length;
    m.matched_map_length += matched;
    if (length == 0 && out_of_scope > 0) --m.map_count;  // wholly out of scope
    if (matched >= 0.5 * length && length > 0) ++m.matched_map;
    double best = 0;
    for (const auto& [line, w] : votes)
      if (w > best) best = w, follows[i] = line;
  }
  // truth side: covered length
  for (std::size_t j = 0; j < tl.size(); ++j) {
    const auto s = aggregate::resamplePolyline(tl[j], p.sample_step);
    double covered = 0, length = 0;
    for (std::size_t k = 1; k < s.size(); ++k) {
      const Vec3 c = 0.5 * (s[k - 1] + s[k]);
      const double len = (s[k] - s[k - 1]).norm();
      length += len;
      if (mindex.nearest(c, tol, nullptr, nullptr) <= tol) covered += len;
    }
    m.truth_length += length;
    m.covered_truth_length += covered;
    if (covered >= 0.5 * length && length > 0) ++m.matched_truth;
  }
  m.completeness = m.truth_length > 0 ? m.covered_truth_length / m.truth_length : 0.0;
  m.redundancy =
      m.map_length > 0
          ? (m.map_length - std::min(m.matched_map_length, m.covered_truth_length)) / m.map_length
          : 0.0;
  m.absolute = errorStats(abs_errors);

  // relative precision: lane widths at stations along every truth line
  std::vector<double> rel_errors;
  constexpr double kMaxCos = 0.26;  // foot direction within ~15 deg of the line normal
  for (std::size_t a = 0; a < tl.size(); ++a) {
    const auto s = aggregate::resamplePolyline(tl[a], p.sample_step);
    for (std::size_t k = 0; k < s.size(); ++k) {
      const Vec3& t = s[k];
      const Eigen::Vector2d tangent =
          (s[std::min(k + 1, s.size() - 1)] - s[k == 0 ? 0 : k - 1]).head<2>().normalized();
      std::pair<double, std::pair<int, Vec3>> side[2] = {{kInf, {-1, Vec3()}},
                                                         {kInf, {-1, Vec3()}}};
      tindex.perLine(t, p.lane_width_max, [&](int b, const Vec3& f, double d) {
        if (std::size_t(b) == a || d < p.lane_width_min) return;
        const Eigen::Vector2d v = (f - t).head<2>() / d;
        if (std::abs(v.dot(tangent)) > kMaxCos) return;
        const int left = tangent.x() * v.y() - tangent.y() * v.x() > 0 ? 1 : 0;
        if (d < side[left].first) side[left] = {d, {b, f}};
      });
      for (const auto& sd : side) {
        if (sd.second.first < 0) continue;
        const int b = sd.second.first;
        const Vec3& f = sd.second.second;
        Vec3 ma, mb;
        const double da =
            mindex.nearest(t, tol, &ma, nullptr, [&](int l) { return follows[l] == int(a); });
        const double db =
            mindex.nearest(f, tol, &mb, nullptr, [&](int l) { return follows[l] == b; });
        if (da > tol || db > tol) continue;
        rel_errors.push_back(std::abs((ma - mb).head<2>().norm() - sd.first));
      }
    }
  }
  m.relative = errorStats(rel_errors);
  return m;
}

// Distance of a map element's centre c from a true element: from the true centre; for
// segments (stop lines) whose centre is farther than the tolerance from the true centre, from
// the true segment, so that a stop line seen only in part (a camera cuts the stop lines of
// neighbouring lanes) matches at its placement error across the line.
double elementDistance(const Vec3& c, const MapInstance& t, const Vec3& t_centre, bool segment,
                       double tolerance, Vec3* displacement) {
  const double dc = (c - t_centre).norm();
  if (dc <= tolerance || !segment || t.points.size() < 2) {
    if (displacement) *displacement = c - t_centre;
    return dc;
  }
  Vec3 foot;
  aggregate::distanceToPolyline2d(c, t.points, &foot);
  const Vec3 d(c.x() - foot.x(), c.y() - foot.y(), c.z() - t_centre.z());
  if (displacement) *displacement = d;
  return d.norm();
}

ClassMetrics evaluateDiscrete(const std::vector<const MapInstance*>& map_all,
                              const std::vector<const MapInstance*>& truth,
                              const std::vector<const MapInstance*>& unscored,
                              const MapEvalParams& p, bool segments) {
  ClassMetrics m;
  m.truth_count = truth.size();
  std::vector<Vec3> tc, uc, mc;
  for (const auto* t : truth) tc.push_back(instanceCentre(*t));
  for (const auto* u : unscored) uc.push_back(instanceCentre(*u));
  // Out of scope: map elements that match no scored true element but an unscored one.
  std::vector<const MapInstance*> map;
  auto near = [&](const Vec3& c, const std::vector<const MapInstance*>& ts,
                  const std::vector<Vec3>& cs) {
    for (std::size_t j = 0; j < ts.size(); ++j)
      if (elementDistance(c, *ts[j], cs[j], segments, p.discrete_tolerance, nullptr) <=
          p.discrete_tolerance)
        return true;
    return false;
  };
  for (const auto* i : map_all) {
    const Vec3 c = instanceCentre(*i);
    if (!near(c, truth, tc) && near(c, unscored, uc)) continue;
    map.push_back(i);
    mc.push_back(c);
  }
  m.map_count = map.size();
  // greedy one-to-one matching by increasing distance
  std::vector<std::tuple<double, std::size_t, std::size_t>> pairs;
  for (std::size_t j = 0; j < tc.size(); ++j)
    for (std::size_t i = 0; i < mc.size(); ++i) {
      const double d =
          elementDistance(mc[i], *truth[j], tc[j], segments, p.discrete_tolerance, nullptr);
      if (d <= p.discrete_tolerance) pairs.emplace_back(d, j, i);
    }
  std::sort(pairs.begin(), pairs.end());
  std::vector<int> match_of_truth(tc.size(), -1), match_of_map(mc.size(), -1);
  std::vector<Vec3> placed(tc.size());  // true centre + the matched element's displacement
  std::vector<double> abs_errors;
  for (const auto& [d, j, i] : pairs) {
    if (match_of_truth[j] >= 0 || match_of_map[i] >= 0) continue;
    match_of_truth[j] = int(i);
    match_of_map[i] = int(j);
    Vec3 disp;
    elementDistance(mc[i], *truth[j], tc[j], segments, p.discrete_tolerance, &disp);
    placed[j] = tc[j] + disp;
    abs_errors.push_back(d);
  }
  m.matched_truth = m.matched_map = abs_errors.size();
  m.completeness = tc.empty() ? 0.0 : double(m.matched_truth) / double(tc.size());
  m.redundancy = mc.empty() ? 0.0 : double(mc.size() - m.matched_map) / double(mc.size());
  m.absolute = errorStats(abs_errors);
  // relative precision: distance to the nearest truth neighbour of the same class
  std::vector<double> rel_errors;
  for (std::size_t a = 0; a < tc.size(); ++a) {
    std::size_t b = a;
    double best = p.neighbour_max_distance;
    for (std::size_t j = 0; j < tc.size(); ++j)
      if (j != a && (tc[j] - tc[a]).norm() <= best) best = (tc[j] - tc[a]).norm(), b = j;
    if (b == a || match_of_truth[a] < 0 || match_of_truth[b] < 0) continue;
    const double rd_obs = (placed[a] - placed[b]).norm();
    rel_errors.push_back(std::abs(rd_obs - best));
  }
  m.relative = errorStats(rel_errors);
  return m;
}

}  // namespace

VectorMap inOrigin(const VectorMap& map_in, const geo::GeoOrigin& origin) {
  VectorMap map = map_in;
  if (geo::sameOrigin(map.origin, origin)) return map;
  const geo::EnuConverter from(map.origin), to(origin);
  for (auto& inst : map.instances)
    for (auto& q : inst.points) q = to.toEnu(from.toWgs84(q));
  map.origin = origin;
  return map;
}

MapMetrics evaluateMap(const VectorMap& map_in, const VectorMap& truth, const MapEvalParams& p,
                       const VectorMap* unscored) {
  const VectorMap map = inOrigin(map_in, truth.origin);
  MapMetrics out;
  for (int c = 0; c < kNumCrowdClasses; ++c) {
    const CrowdClass cls = CrowdClass(c);
    std::vector<const MapInstance*> mi, ti, ui;
    for (const auto& i : map.instances)
      if (i.cls == cls) mi.push_back(&i);
    for (const auto& i : truth.instances)
      if (i.cls == cls) ti.push_back(&i);
    if (unscored)
      for (const auto& i : unscored->instances)
        if (i.cls == cls) ui.push_back(&i);
    if (mi.empty() && ti.empty()) continue;
    const bool segments = cls == CrowdClass::kStopLine;
    ClassMetrics m = cls == CrowdClass::kLaneLine ? evaluateLines(mi, ti, ui, p)
                                                  : evaluateDiscrete(mi, ti, ui, p, segments);
    m.cls = cls;
    out.classes.push_back(std::move(m));
  }
  return out;
}

VectorMap clipToCoverage(const VectorMap& truth, const std::vector<Pose3>& poses,
                         const CoverageWedge& wedge, VectorMap* outside) {
  const double cell = std::hypot(wedge.range, wedge.lateral);  // farthest covered point
  const double tan_fov =
      wedge.half_fov_deg < 90 ? std::tan(wedge.half_fov_deg * M_PI / 180.0) : 1e18;
  auto key = [&](double x, double y) { return voxel_grid::cellKey2d(x, y, cell); };
  std::unordered_multimap<int64_t, const Pose3*> grid;
  for (const auto& p : poses) grid.emplace(key(p.translation().x(), p.translation().y()), &p);
  auto covered = [&](const Vec3& q) {
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy) {
        auto r = grid.equal_range(key(q.x() + dx * cell, q.y() + dy * cell));
        for (auto it = r.first; it != r.second; ++it) {
          const Eigen::Matrix3d R = it->second->linear();
          const Vec3 d = q - it->second->translation();
          const double bx = R.col(0).head<2>().dot(d.head<2>()),
                       by = std::abs(R.col(1).head<2>().dot(d.head<2>()));
          if (bx >= wedge.apex_x && bx <= wedge.range && by <= wedge.lateral &&
              by <= (bx - wedge.apex_x) * tan_fov)
            return true;
        }
      }
    return false;
  };
  constexpr double kMinPiece = 1.0;  // m
  VectorMap out = truth;
  out.instances.clear();
  if (outside) {
    *outside = truth;
    outside->instances.clear();
  }
  int64_t next_id = 1;
  for (const auto& i : truth.instances) next_id = std::max(next_id, i.id + 1);
  for (const auto& inst : truth.instances) {
    if (geometryKind(inst.cls) != GeometryKind::kLine) {
      if (covered(instanceCentre(inst)))
        out.instances.push_back(inst);
      else if (outside)
        outside->instances.push_back(inst);
      continue;
    }
    std::vector<Vec3> piece, rest;  // covered piece, uncovered piece
    auto flush_rest = [&] {
      if (outside && rest.size() >= 2) {
        MapInstance m = inst;
        m.points = rest;
        m.bezier.clear();
        outside->instances.push_back(std::move(m));
      }
      rest.clear();
    };
    bool first = true;
    auto flush = [&] {
      if (piece.size() >= 2 && polylineLength(piece) >= kMinPiece) {
        MapInstance m = inst;
        m.points = piece;
        m.bezier.clear();
        if (!first) m.id = next_id++;
        first = false;
        out.instances.push_back(std::move(m));
      }
      piece.clear();
    };
    for (const auto& q : aggregate::resamplePolyline(inst.points, 0.5)) {
      if (covered(q)) {
        if (!rest.empty()) rest.push_back(q);  // the uncovered piece reaches the boundary
        flush_rest();
        piece.push_back(q);
      } else {
        if (rest.empty() && !piece.empty()) rest.push_back(piece.back());
        flush();
        rest.push_back(q);
      }
    }
    flush();
    flush_rest();
  }
  return out;
}

nlohmann::json toJson(const ClassMetrics& m) {
  nlohmann::json j = {{"class", crowdClassName(m.cls)},
                      {"measure", m.by_length ? "length" : "count"},
                      {"truth_count", m.truth_count},
                      {"map_count", m.map_count},
                      {"matched_truth", m.matched_truth},
                      {"matched_map", m.matched_map},
                      {"completeness", m.completeness},
                      {"redundancy", m.redundancy},
                      {"relative_precision_m", m.relative.count ? nlohmann::json(m.relative.mean)
                                                                : nlohmann::json(nullptr)},
                      {"relative_error", toJson(m.relative)},
                      {"absolute_error", toJson(m.absolute)}};
  if (!m.relative.count)
    j["relative_precision_reason"] = m.truth_count == 0 ? "no truth element of this class"
                                     : m.map_count == 0 ? "no map element of this class"
                                                        : "no map element matched the truth";
  if (m.completeness_observed >= 0) {
    j["completeness_observed"] = m.completeness_observed;
    j["truth_observed"] = m.truth_observed;
  }
  if (m.by_length) {
    j["truth_length_m"] = m.truth_length;
    j["map_length_m"] = m.map_length;
    j["covered_truth_length_m"] = m.covered_truth_length;
    j["matched_map_length_m"] = m.matched_map_length;
  }
  return j;
}

nlohmann::json toJson(const MapMetrics& m) {
  nlohmann::json classes = nlohmann::json::array();
  for (const auto& c : m.classes) classes.push_back(toJson(c));
  return classes;
}

}  // namespace mapfuse::eval
