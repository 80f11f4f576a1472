#include "mapfuse/lanelet/plan.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <unordered_map>

#include "joins.hpp"
#include "kinks.hpp"
#include "ring_index.hpp"

namespace mapfuse::lanelet {

namespace {

constexpr double kStationStep = 1.0;        // m between stations where neighbours are sought
constexpr double kMinParallel = 0.9063;     // cos 25 deg between the two bounds
constexpr double kRunBreak = 3.0;           // m of missing neighbour that ends a pair interval
constexpr double kCutSnap = 1.0;            // m; a cut this close to another is the same cut
constexpr double kMinPiece = 0.5;           // m; shorter pieces give no lanelet
constexpr double kGridCell = 5.0;           // m, segment and drive-sample grid
constexpr double kDriveStep = 2.0;          // m between drive samples used as votes
constexpr int kMaxPropagation = 20;         // rounds of cut propagation
constexpr double kConnectorStep = 1.0;      // m between drive samples tracing connections
constexpr double kConnectorEnd = 4.0;       // m; the drive leaves / enters within this of the ends
constexpr double kMinConnectorBound = 0.1;  // m; shorter is one node (io merges below 0.0502 m)

using V3 = Eigen::Vector3d;
using Poly = std::vector<V3>;

std::vector<double> arcLengths(const Poly& line) {
  std::vector<double> s(line.size(), 0.0);
  for (std::size_t i = 1; i < line.size(); ++i)
    s[i] = s[i - 1] + (line[i] - line[i - 1]).head<2>().norm();
  return s;
}

/// Point and unit xy tangent at arc length s.
std::pair<V3, Eigen::Vector2d> sampleAt(const Poly& line, const std::vector<double>& cum,
                                        double s) {
  s = std::clamp(s, 0.0, cum.back());
  std::size_t i =
      static_cast<std::size_t>(std::upper_bound(cum.begin(), cum.end(), s) - cum.begin());
  i = std::clamp<std::size_t>(i, 1, line.size() - 1);
  const double seg = cum[i] - cum[i - 1];
  const double a = seg > 0 ? (s - cum[i - 1]) / seg : 0.0;
  Eigen::Vector2d t = (line[i] - line[i - 1]).head<2>();
  t = t.norm() > 1e-12 ? Eigen::Vector2d(t.normalized()) : Eigen::Vector2d(1, 0);
  return {line[i - 1] + a * (line[i] - line[i - 1]), t};
}

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

using Cell = std::pair<int64_t, int64_t>;
Cell cellOf(double x, double y) {
  return {static_cast<int64_t>(std::floor(x / kGridCell)),
          static_cast<int64_t>(std::floor(y / kGridCell))};
}

/// Segments of all lane lines on a grid, for the lateral rays.
struct SegmentGrid {
  struct Seg {
    std::size_t line, index;
  };
  std::map<Cell, std::vector<Seg>> cells;

  void add(std::size_t line, const Poly& pts) {
    for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
      const Cell a =
          cellOf(std::min(pts[k].x(), pts[k + 1].x()), std::min(pts[k].y(), pts[k + 1].y()));
      const Cell b =
          cellOf(std::max(pts[k].x(), pts[k + 1].x()), std::max(pts[k].y(), pts[k + 1].y()));
      for (int64_t x = a.first; x <= b.first; ++x)
        for (int64_t y = a.second; y <= b.second; ++y) cells[{x, y}].push_back({line, k});
    }
  }
};

/// The neighbour a lateral ray meets: line, arc length on it, distance.
struct Hit {
  long line = -1;
  double s = 0.0;
  double w = 0.0;
};

/// One sample of a pair of neighbouring lines: arc length on the lower and the higher line.
struct PairSample {
  double a, b;
};

/// Piecewise-linear map from arc length on one line to the other through a pair's samples,
/// `sorted` by the key side (a when forward, b otherwise); clamped at the ends.
double mapThrough(const std::vector<PairSample>& sorted, double s, bool forward) {
  auto key = [&](const PairSample& p) { return forward ? p.a : p.b; };
  auto val = [&](const PairSample& p) { return forward ? p.b : p.a; };
  const auto it = std::upper_bound(sorted.begin(), sorted.end(), s,
                                   [&](double x, const PairSample& p) { return x < key(p); });
  if (it == sorted.begin()) return val(sorted.front());
  if (it == sorted.end()) return val(sorted.back());
  const PairSample& lo = *(it - 1);
  const PairSample& hi = *it;
  const double span = key(hi) - key(lo);
  const double u = span > 0 ? (s - key(lo)) / span : 0.0;
  return val(lo) + u * (val(hi) - val(lo));
}

struct PairInterval {
  std::size_t a, b;                 ///< line indices (plan order), a < b
  std::vector<PairSample> samples;  ///< sorted by a
  std::vector<PairSample> by_b;     ///< the same, sorted by b
  double a0, a1, b0, b1;            ///< extent on each line
};

/// Adds cut s to a sorted cut list unless one lies within kCutSnap; true when added.
bool addCut(std::vector<double>& cuts, double s, double length) {
  if (s <= kCutSnap || s >= length - kCutSnap) return false;
  for (double c : cuts)
    if (std::abs(c - s) < kCutSnap) return false;
  cuts.insert(std::upper_bound(cuts.begin(), cuts.end(), s), s);
  return true;
}

std::size_t nearestCut(const std::vector<double>& cuts, double s) {
  std::size_t best = 0;
  for (std::size_t k = 1; k < cuts.size(); ++k)
    if (std::abs(cuts[k] - s) < std::abs(cuts[best] - s)) best = k;
  return best;
}

/// Resamples two bounds at equal arc fractions and returns the centre line (n points).
Poly centreOf(const Poly& left, const Poly& right) {
  const auto cl = arcLengths(left), cr = arcLengths(right);
  const int n = std::max(2, static_cast<int>(std::ceil(std::max(cl.back(), cr.back()))) + 1);
  Poly c;
  for (int k = 0; k < n; ++k) {
    const double f = double(k) / (n - 1);
    c.push_back(
        0.5 * (sampleAt(left, cl, f * cl.back()).first + sampleAt(right, cr, f * cr.back()).first));
  }
  return c;
}

/// Cubic Hermite curve from p0 (direction t0) to p1 (direction t1), sampled every ~1 m.
Poly hermite(const V3& p0, const Eigen::Vector2d& t0, const V3& p1, const Eigen::Vector2d& t1) {
  const double chord = (p1 - p0).head<2>().norm();
  const V3 m0(t0.x() * chord, t0.y() * chord, 0.0), m1(t1.x() * chord, t1.y() * chord, 0.0);
  const int n = std::max(2, static_cast<int>(std::ceil(chord / kConnectorStep)));
  Poly out;
  for (int k = 0; k <= n; ++k) {
    const double u = double(k) / n, u2 = u * u, u3 = u2 * u;
    out.push_back((2 * u3 - 3 * u2 + 1) * p0 + (u3 - 2 * u2 + u) * m0 + (-2 * u3 + 3 * u2) * p1 +
                  (u3 - u2) * m1);
  }
  return out;
}

}  // namespace

bool insideRingXY(const std::vector<Eigen::Vector3d>& ring, const Eigen::Vector3d& p) {
  bool inside = false;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    const V3& a = ring[i];
    const V3& b = ring[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      inside = !inside;
  }
  return inside;
}

std::vector<Eigen::AlignedBox2d> laneletBoxes(const LaneletPlan& plan) {
  std::vector<Eigen::AlignedBox2d> out(plan.lanelets.size());  // empty boxes
  for (std::size_t l = 0; l < plan.lanelets.size(); ++l)
    for (const auto& p : plan.lanelets[l].ring) out[l].extend(p.head<2>());
  return out;
}

std::pair<std::size_t, bool> boundEnd(const LaneletPlan& plan, const LaneletPlan::Lanelet& ll,
                                      bool left, bool at_end) {
  const std::size_t piece = left ? ll.left : ll.right;
  const Poly pts = piecePoints(plan, piece);
  const V3& target = at_end ? ll.centre.back() : ll.centre.front();
  return {piece, (pts.back() - target).norm() < (pts.front() - target).norm()};
}

std::vector<Eigen::Vector3d> piecePoints(const LaneletPlan& plan, std::size_t piece) {
  const auto& pc = plan.pieces[piece];
  const auto& line = plan.lines[pc.line];
  return {line.points.begin() + static_cast<long>(line.cuts[pc.cut]),
          line.points.begin() + static_cast<long>(line.cuts[pc.cut + 1]) + 1};
}

namespace {

/// The connections drives made: where a drive leaves one one-way lanelet at its end and enters
/// another at its start after an unmarked stretch, (from, to) with the number of drives, in the
/// order they were first seen.
std::vector<std::pair<std::pair<std::size_t, std::size_t>, int>> driveConnections(
    const LaneletPlan& plan, const std::vector<DrivePath>& drives,
    const LaneletSettings& settings) {
  std::map<Cell, std::vector<std::size_t>> grid;
  std::vector<detail::RingIndex> rings;  // the test of every drive sample against the rings
  rings.reserve(plan.lanelets.size());
  for (const auto& ll : plan.lanelets) rings.emplace_back(ll.ring);
  for (std::size_t l = 0; l < plan.lanelets.size(); ++l) {
    const auto& ll = plan.lanelets[l];
    if (!ll.direction_known) continue;
    V3 lo = ll.ring.front(), hi = lo;
    for (const auto& p : ll.ring) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    const Cell a = cellOf(lo.x(), lo.y()), b = cellOf(hi.x(), hi.y());
    for (int64_t x = a.first; x <= b.first; ++x)
      for (int64_t y = a.second; y <= b.second; ++y) grid[{x, y}].push_back(l);
  }
  auto containing = [&](const V3& p, const Eigen::Vector2d& t) -> long {
    const auto it = grid.find(cellOf(p.x(), p.y()));
    if (it == grid.end()) return -1;
    for (std::size_t l : it->second) {
      const auto& ll = plan.lanelets[l];
      if (!rings[l].contains(p)) continue;
      const Eigen::Vector2d d = (ll.centre.back() - ll.centre.front()).head<2>();
      if (d.dot(t) > 0) return static_cast<long>(l);
    }
    return -1;
  };
  std::vector<std::pair<std::pair<std::size_t, std::size_t>, int>> made;
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> index;
  for (const auto& d : drives) {
    if (d.size() < 2) continue;
    const auto dc = arcLengths(d);
    long last = -1;
    double left_at = 0.0;
    for (double s = 0.0; s <= dc.back(); s += kConnectorStep) {
      const auto [p, t] = sampleAt(d, dc, s);
      const long l = containing(p, t);
      if (l < 0) continue;
      if (last >= 0 && l != last && s - left_at > kConnectorStep &&
          s - left_at <= settings.max_connector) {
        const auto& a = plan.lanelets[static_cast<std::size_t>(last)];
        const auto& b = plan.lanelets[static_cast<std::size_t>(l)];
        const V3 exit_p = sampleAt(d, dc, left_at).first;
        if ((exit_p - a.centre.back()).head<2>().norm() <= kConnectorEnd &&
            (p - b.centre.front()).head<2>().norm() <= kConnectorEnd) {
          const auto key =
              std::make_pair(static_cast<std::size_t>(last), static_cast<std::size_t>(l));
          const auto [it, fresh] = index.try_emplace(key, made.size());
          if (fresh) made.push_back({key, 0});
          ++made[it->second].second;
        }
      }
      last = l;
      left_at = s;
    }
  }
  return made;
}

/// Connector lanelets for the drives' connections (driveConnections). Bounds run from the first
/// lanelet's bound ends to the second's bound starts; a connection whose bounds already meet on
/// one side would need a bound of one node there, which no lanelet can have (Lanelet2 routes
/// nothing through it), and gets none (`one_sided_connections`).
void addConnectors(LaneletPlan& plan, const std::vector<DrivePath>& drives,
                   const LaneletSettings& settings) {
  auto endPoint = [&](const LaneletPlan::Lanelet& ll, bool left, bool at_end) {
    const auto [piece, last_point] = boundEnd(plan, ll, left, at_end);
    const Poly pts = piecePoints(plan, piece);
    return last_point ? pts.back() : pts.front();
  };
  auto direction = [](const Poly& c, bool at_end) {
    const std::size_t n = c.size();
    const Eigen::Vector2d d = (at_end ? c[n - 1] - c[n - 2] : c[1] - c[0]).head<2>();
    return d.norm() > 1e-9 ? Eigen::Vector2d(d.normalized()) : Eigen::Vector2d(1, 0);
  };
  for (const auto& [key, count] : driveConnections(plan, drives, settings)) {
    const auto& a = plan.lanelets[key.first];
    const auto& b = plan.lanelets[key.second];
    const V3 al = endPoint(a, true, true), bl = endPoint(b, true, false);
    const V3 ar = endPoint(a, false, true), br = endPoint(b, false, false);
    if ((bl - al).norm() < kMinConnectorBound || (br - ar).norm() < kMinConnectorBound) {
      ++plan.one_sided_connections;
      continue;
    }
    LaneletPlan::Connector c;
    c.from = key.first;
    c.to = key.second;
    c.drives = count;
    const Eigen::Vector2d ta = direction(a.centre, true), tb = direction(b.centre, false);
    // a short connector between bound ends that do not face each other bends its Hermite
    // curve within a metre (MONAEast, frames level: 45 degrees over 0.65 m, curvature > 0.5 for
    // lanelet2_validate): interior vertices above max_curvature go as on the lane lines
    c.left = detail::removeKinks(hermite(al, ta, bl, tb), settings.max_curvature);
    c.right = detail::removeKinks(hermite(ar, ta, br, tb), settings.max_curvature);
    plan.connectors.push_back(std::move(c));
  }
}

/// The lane lines long enough to bound a lanelet, without their kinks (kinks.hpp), with their
/// arc lengths and segment grid.
struct LineSet {
  std::vector<std::size_t> inst;  ///< index in VectorMap::instances
  std::vector<Poly> lines;
  std::vector<std::vector<double>> cum;
  SegmentGrid grid;
  int kink_vertices_removed = 0;
  double kink_max_deviation = 0.0;
  detail::LineJoins joins;  ///< facing ends of lines continuing each other (joins.hpp)
};

LineSet collectLines(const VectorMap& map, const LaneletSettings& settings) {
  LineSet set;
  for (std::size_t i = 0; i < map.instances.size(); ++i) {
    const auto& m = map.instances[i];
    if (m.cls != CrowdClass::kLaneLine || m.points.size() < 2) continue;
    if (polylineLength(m.points) < settings.min_length) continue;
    set.inst.push_back(i);
    set.lines.push_back(m.points);
  }
  // joined before the kinks go, so that a bend the join leaves at a moved end goes with them
  set.joins = detail::joinLineEnds(set.lines, settings.join_gap);
  for (auto& line : set.lines) {
    detail::KinkRemoval kinks;
    line = detail::removeKinks(line, settings.max_curvature, &kinks);
    set.kink_vertices_removed += kinks.removed;
    set.kink_max_deviation = std::max(set.kink_max_deviation, kinks.max_deviation);
  }
  set.cum.resize(set.lines.size());
  for (std::size_t i = 0; i < set.lines.size(); ++i) {
    set.cum[i] = arcLengths(set.lines[i]);
    set.grid.add(i, set.lines[i]);
  }
  return set;
}

/// The nearest line across from a station of line i, if it is a lane width away and parallel.
Hit cast(const LineSet& set, std::size_t i, const V3& p, const Eigen::Vector2d& t, double side,
         const LaneletSettings& settings) {
  const auto& lines = set.lines;
  const auto& cum = set.cum;
  const auto& grid = set.grid;
  const Eigen::Vector2d dir = side * Eigen::Vector2d(-t.y(), t.x());
  const Eigen::Vector2d o = p.head<2>(), e = o + settings.max_width * dir;
  const Cell lo = cellOf(std::min(o.x(), e.x()), std::min(o.y(), e.y()));
  const Cell hi = cellOf(std::max(o.x(), e.x()), std::max(o.y(), e.y()));
  Hit best;
  best.w = settings.max_width + 1.0;
  Eigen::Vector2d best_dir(0, 0);
  std::set<std::pair<std::size_t, std::size_t>> seen;
  for (int64_t x = lo.first; x <= hi.first; ++x)
    for (int64_t y = lo.second; y <= hi.second; ++y) {
      const auto it = grid.cells.find({x, y});
      if (it == grid.cells.end()) continue;
      for (const auto& sg : it->second) {
        if (sg.line == i || !seen.insert({sg.line, sg.index}).second) continue;
        const Eigen::Vector2d a = lines[sg.line][sg.index].head<2>();
        const Eigen::Vector2d b = lines[sg.line][sg.index + 1].head<2>();
        const Eigen::Vector2d d = b - a;
        const double den = cross2(dir, d);
        if (std::abs(den) < 1e-12) continue;
        const double w = cross2(a - o, d) / den;    // along the ray
        const double u = cross2(a - o, dir) / den;  // along the segment
        if (u < 0.0 || u > 1.0 || w <= 0.05 || w >= best.w) continue;
        best = {static_cast<long>(sg.line), cum[sg.line][sg.index] + u * d.norm(), w};
        best_dir = d.normalized();
      }
    }
  if (best.line < 0 || best.w < settings.min_width || best.w > settings.max_width ||
      std::abs(best_dir.dot(t)) < kMinParallel)
    return Hit{};
  return best;
}

/// Pair samples from every station of every line, both sides.
std::map<std::pair<std::size_t, std::size_t>, std::vector<PairSample>> pairSamples(
    const LineSet& set, const LaneletSettings& settings) {
  const std::size_t n = set.lines.size();
  const auto& lines = set.lines;
  const auto& cum = set.cum;
  std::map<std::pair<std::size_t, std::size_t>, std::vector<PairSample>> pair_samples;
  for (std::size_t i = 0; i < n; ++i) {
    const double L = cum[i].back();
    const int stations = std::max(1, static_cast<int>(std::floor(L / kStationStep)));
    for (int k = 0; k <= stations; ++k) {
      const double s = L * k / stations;
      const auto [p, t] = sampleAt(lines[i], cum[i], s);
      for (double side : {1.0, -1.0}) {
        const Hit h = cast(set, i, p, t, side, settings);
        if (h.line < 0) continue;
        const std::size_t j = static_cast<std::size_t>(h.line);
        if (i < j)
          pair_samples[{i, j}].push_back({s, h.s});
        else
          pair_samples[{j, i}].push_back({h.s, s});
      }
    }
  }
  return pair_samples;
}

/// Pair intervals: runs of samples along the lower line without a long gap.
std::vector<PairInterval> pairIntervals(
    std::map<std::pair<std::size_t, std::size_t>, std::vector<PairSample>>& pair_samples,
    const LaneletSettings& settings) {
  std::vector<PairInterval> intervals;
  for (auto& [key, samples] : pair_samples) {
    std::sort(samples.begin(), samples.end(),
              [](const PairSample& x, const PairSample& y) { return x.a < y.a; });
    std::size_t start = 0;
    for (std::size_t k = 1; k <= samples.size(); ++k) {
      if (k < samples.size() && samples[k].a - samples[k - 1].a <= kRunBreak) continue;
      PairInterval iv;
      iv.a = key.first;
      iv.b = key.second;
      iv.samples.assign(samples.begin() + static_cast<long>(start),
                        samples.begin() + static_cast<long>(k));
      iv.a0 = iv.samples.front().a;
      iv.a1 = iv.samples.back().a;
      iv.b0 = iv.b1 = iv.samples.front().b;
      for (const auto& p : iv.samples) iv.b0 = std::min(iv.b0, p.b), iv.b1 = std::max(iv.b1, p.b);
      iv.by_b = iv.samples;
      std::sort(iv.by_b.begin(), iv.by_b.end(),
                [](const PairSample& x, const PairSample& y) { return x.b < y.b; });
      if (iv.a1 - iv.a0 >= settings.min_length && iv.b1 - iv.b0 >= settings.min_length)
        intervals.push_back(iv);
      start = k;
    }
  }
  return intervals;
}

/// Cuts: line ends, interval ends, then propagated across pairs until side-by-side lanes agree.
std::vector<std::vector<double>> cutLines(const LineSet& set,
                                          const std::vector<PairInterval>& intervals) {
  const std::size_t n = set.lines.size();
  const auto& cum = set.cum;
  std::vector<std::vector<double>> cuts(n);
  for (std::size_t i = 0; i < n; ++i) cuts[i] = {0.0, cum[i].back()};
  for (const auto& iv : intervals) {
    addCut(cuts[iv.a], iv.a0, cum[iv.a].back());
    addCut(cuts[iv.a], iv.a1, cum[iv.a].back());
    addCut(cuts[iv.b], iv.b0, cum[iv.b].back());
    addCut(cuts[iv.b], iv.b1, cum[iv.b].back());
  }
  for (int round = 0; round < kMaxPropagation; ++round) {
    bool changed = false;
    for (const auto& iv : intervals) {
      for (double c : std::vector<double>(cuts[iv.a]))
        if (c > iv.a0 + kCutSnap && c < iv.a1 - kCutSnap)
          changed |= addCut(cuts[iv.b], mapThrough(iv.samples, c, true), cum[iv.b].back());
      for (double c : std::vector<double>(cuts[iv.b]))
        if (c > iv.b0 + kCutSnap && c < iv.b1 - kCutSnap)
          changed |= addCut(cuts[iv.a], mapThrough(iv.by_b, c, false), cum[iv.a].back());
    }
    if (!changed) break;
  }
  return cuts;
}

/// Lines with their cut points inserted, pieces, and lanelets: consecutive cuts on the lower
/// line and the matching cuts on the higher, with their geometry.
LaneletPlan buildLanelets(const LineSet& set, const std::vector<std::vector<double>>& cuts,
                          const std::vector<PairInterval>& intervals) {
  const std::size_t n = set.lines.size();
  const auto& lines = set.lines;
  const auto& cum = set.cum;
  const auto& inst = set.inst;
  LaneletPlan plan;
  std::vector<long> plan_line(n, -1);
  auto planLine = [&](std::size_t i) {
    if (plan_line[i] >= 0) return static_cast<std::size_t>(plan_line[i]);
    LaneletPlan::Line L;
    L.instance = inst[i];
    std::size_t v = 0;
    for (double c : cuts[i]) {
      while (v < lines[i].size() && cum[i][v] < c - 1e-6) L.points.push_back(lines[i][v++]);
      if (v < lines[i].size() && std::abs(cum[i][v] - c) <= 1e-6) {
        L.points.push_back(lines[i][v++]);
      } else {
        L.points.push_back(sampleAt(lines[i], cum[i], c).first);
      }
      L.cuts.push_back(L.points.size() - 1);
    }
    plan_line[i] = static_cast<long>(plan.lines.size());
    plan.lines.push_back(std::move(L));
    return plan.lines.size() - 1;
  };
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> piece_index;
  auto piece = [&](std::size_t i, std::size_t k) {
    const std::size_t l = planLine(i);
    const auto it = piece_index.find({l, k});
    if (it != piece_index.end()) return it->second;
    plan.pieces.push_back({l, k});
    piece_index[{l, k}] = plan.pieces.size() - 1;
    return plan.pieces.size() - 1;
  };
  // Lanelets: consecutive cuts on the lower line and the matching cuts on the higher.
  std::set<std::pair<std::size_t, std::size_t>> made;
  for (const auto& iv : intervals) {
    const std::size_t ka = nearestCut(cuts[iv.a], iv.a0), kb = nearestCut(cuts[iv.a], iv.a1);
    for (std::size_t k = ka; k < kb; ++k) {
      const double c0 = cuts[iv.a][k], c1 = cuts[iv.a][k + 1];
      if (c1 - c0 < kMinPiece) continue;
      const std::size_t q0 = nearestCut(cuts[iv.b], mapThrough(iv.samples, c0, true));
      const std::size_t q1 = nearestCut(cuts[iv.b], mapThrough(iv.samples, c1, true));
      const std::size_t qlo = std::min(q0, q1);
      if (std::max(q0, q1) - qlo != 1 || cuts[iv.b][qlo + 1] - cuts[iv.b][qlo] < kMinPiece) {
        ++plan.unmatched_pieces;
        continue;
      }
      const std::size_t pa = piece(iv.a, k), pb = piece(iv.b, qlo);
      if (!made.insert({pa, pb}).second) continue;
      LaneletPlan::Lanelet ll;
      ll.left = pa;
      ll.right = pb;
      plan.lanelets.push_back(ll);
    }
  }
  return plan;
}

/// Lanelet2's routing graph takes a lanelet sharing a bound with another as its neighbour on
/// that side and requires the relation to hold back (checkValidity: "isn't the closest lanelet
/// the other way round"), so a piece may bound one lanelet on each of its sides. Where several
/// pairs put lanelets on one side of a piece (short pieces at junction mouths paired with two
/// lines), the one whose other bound lies nearest stays; the others are dropped and counted.
void dropSameSideLanelets(LaneletPlan& plan) {
  struct Use {
    std::size_t lanelet;
    double distance;  // m between the piece's middle and the other bound's middle
  };
  std::map<std::pair<std::size_t, int>, std::vector<Use>> uses;  // (piece, side) -> lanelets
  auto middle = [&](std::size_t piece) {
    const Poly pts = piecePoints(plan, piece);
    const auto c = arcLengths(pts);
    return sampleAt(pts, c, 0.5 * c.back()).first;
  };
  for (std::size_t l = 0; l < plan.lanelets.size(); ++l) {
    const auto& ll = plan.lanelets[l];
    for (const auto& [piece, other] :
         {std::make_pair(ll.left, ll.right), std::make_pair(ll.right, ll.left)}) {
      const Poly pts = piecePoints(plan, piece);
      const Eigen::Vector2d along = (pts.back() - pts.front()).head<2>();
      const V3 a = middle(piece), b = middle(other);
      const int side = cross2(along, (b - a).head<2>()) >= 0 ? 1 : -1;
      uses[{piece, side}].push_back({l, (b - a).head<2>().norm()});
    }
  }
  std::vector<bool> drop(plan.lanelets.size(), false);
  for (auto& [key, list] : uses) {
    if (list.size() < 2) continue;
    std::sort(list.begin(), list.end(),
              [](const Use& x, const Use& y) { return x.distance < y.distance; });
    for (std::size_t k = 1; k < list.size(); ++k) drop[list[k].lanelet] = true;
  }
  std::vector<LaneletPlan::Lanelet> kept;
  for (std::size_t l = 0; l < plan.lanelets.size(); ++l)
    if (!drop[l]) kept.push_back(plan.lanelets[l]);
  plan.same_side_lanelets_dropped = static_cast<int>(plan.lanelets.size() - kept.size());
  plan.lanelets = std::move(kept);
}

/// Centre line and outline of each lanelet, bounds aligned with the left piece.
void laneletGeometry(LaneletPlan& plan) {
  for (auto& ll : plan.lanelets) {
    const Poly left = piecePoints(plan, ll.left);
    Poly right = piecePoints(plan, ll.right);
    if ((left.front() - right.front()).norm() + (left.back() - right.back()).norm() >
        (left.front() - right.back()).norm() + (left.back() - right.front()).norm())
      std::reverse(right.begin(), right.end());
    ll.centre = centreOf(left, right);
    ll.ring = left;
    ll.ring.insert(ll.ring.end(), right.rbegin(), right.rend());
  }
}

/// Travel direction: votes of drive samples inside each lanelet.
void voteByDrives(LaneletPlan& plan, const std::vector<DrivePath>& drives) {
  std::map<Cell, std::vector<std::pair<V3, Eigen::Vector2d>>> drive_grid;
  for (const auto& d : drives) {
    if (d.size() < 2) continue;
    const auto dc = arcLengths(d);
    for (double s = 0.0; s <= dc.back(); s += kDriveStep) {
      const auto [p, t] = sampleAt(d, dc, s);
      drive_grid[cellOf(p.x(), p.y())].push_back({p, t});
    }
  }
  for (auto& ll : plan.lanelets) {
    V3 lo = ll.ring.front(), hi = ll.ring.front();
    for (const auto& p : ll.ring) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    const Cell a = cellOf(lo.x(), lo.y()), b = cellOf(hi.x(), hi.y());
    const auto cc = arcLengths(ll.centre);
    const detail::RingIndex ring(ll.ring);
    for (int64_t x = a.first; x <= b.first; ++x)
      for (int64_t y = a.second; y <= b.second; ++y) {
        const auto it = drive_grid.find({x, y});
        if (it == drive_grid.end()) continue;
        for (const auto& [p, t] : it->second) {
          if (!ring.contains(p)) continue;
          // Lanelet axis at the nearest centre vertex.
          std::size_t best = 0;
          for (std::size_t k = 1; k < ll.centre.size(); ++k)
            if ((ll.centre[k] - p).head<2>().squaredNorm() <
                (ll.centre[best] - p).head<2>().squaredNorm())
              best = k;
          const auto axis = sampleAt(ll.centre, cc, cc[best]).second;
          (axis.dot(t) >= 0 ? ll.votes_for : ll.votes_against) += 1;
        }
      }
  }
}

/// A stop line across one end of a lanelet without drives: traffic drives towards it.
void voteByStopLines(LaneletPlan& plan, const VectorMap& map, const LaneletSettings& settings) {
  std::vector<const MapInstance*> stops;
  for (const auto& m : map.instances)
    if (m.cls == CrowdClass::kStopLine && m.points.size() >= 2) stops.push_back(&m);
  const std::vector<Eigen::AlignedBox2d> boxes = laneletBoxes(plan);
  for (std::size_t l = 0; l < plan.lanelets.size(); ++l) {
    auto& ll = plan.lanelets[l];
    if (ll.votes_for + ll.votes_against > 0) continue;
    const auto cc = arcLengths(ll.centre);
    for (const auto* st : stops) {
      const V3 mid = 0.5 * (st->points.front() + st->points.back());
      if (!boxes[l].contains(mid.head<2>()) || !insideRingXY(ll.ring, mid)) continue;
      std::size_t best = 0;
      for (std::size_t k = 1; k < ll.centre.size(); ++k)
        if ((ll.centre[k] - mid).head<2>().norm() < (ll.centre[best] - mid).head<2>().norm())
          best = k;
      if (cc.back() - cc[best] <= settings.stop_line_end)
        ll.votes_for = 1;  // the stop line ends the lanelet: traffic runs along the centre
      else if (cc[best] <= settings.stop_line_end)
        ll.votes_against = 1;
    }
  }
}

/// Decides a lanelet's direction from its votes, then orients it: the left bound lies left of
/// the travel direction.
void orient(const LaneletPlan& plan, LaneletPlan::Lanelet& ll) {
  ll.direction_known = ll.votes_for > 2 * ll.votes_against || ll.votes_against > 2 * ll.votes_for;
  if (ll.direction_known && ll.votes_against > ll.votes_for) {
    std::reverse(ll.centre.begin(), ll.centre.end());
    std::swap(ll.votes_for, ll.votes_against);
  }
  // Which piece is left of the centre's direction (at its middle)?
  const std::size_t m = ll.centre.size() / 2;
  const Eigen::Vector2d dir =
      (ll.centre[std::min(ll.centre.size() - 1, m + 1)] - ll.centre[m > 0 ? m - 1 : 0]).head<2>();
  const Poly left = piecePoints(plan, ll.left);
  const auto lc = arcLengths(left);
  const V3 lp = sampleAt(left, lc, 0.5 * lc.back()).first;
  if (cross2(dir, (lp - ll.centre[m]).head<2>()) < 0) {
    std::swap(ll.left, ll.right);
    const Poly l2 = piecePoints(plan, ll.left);
    Poly r2 = piecePoints(plan, ll.right);
    if ((l2.front() - r2.front()).norm() + (l2.back() - r2.back()).norm() >
        (l2.front() - r2.back()).norm() + (l2.back() - r2.front()).norm())
      std::reverse(r2.begin(), r2.end());
    ll.ring = l2;
    ll.ring.insert(ll.ring.end(), r2.rbegin(), r2.rend());
  }
}

}  // namespace

std::vector<DrivePath> drivePaths(const std::vector<Lsm>& lsms) {
  std::vector<DrivePath> drives(lsms.size());
  for (std::size_t d = 0; d < lsms.size(); ++d)
    for (const auto& k : lsms[d].keyframes) drives[d].push_back(k.T_frame_body.translation());
  return drives;
}

LaneletPlan planLanelets(const VectorMap& map, const std::vector<DrivePath>& drives,
                         const LaneletSettings& settings) {
  const LineSet set = collectLines(map, settings);
  auto pair_samples = pairSamples(set, settings);
  const std::vector<PairInterval> intervals = pairIntervals(pair_samples, settings);
  LaneletPlan plan = buildLanelets(set, cutLines(set, intervals), intervals);
  plan.kink_vertices_removed = set.kink_vertices_removed;
  plan.kink_max_deviation = set.kink_max_deviation;
  plan.line_ends_joined = set.joins.joined;
  detail::removePieceKinks(plan, settings.max_curvature);
  dropSameSideLanelets(plan);
  laneletGeometry(plan);
  voteByDrives(plan, drives);
  voteByStopLines(plan, map, settings);
  for (auto& ll : plan.lanelets) orient(plan, ll);
  // Lanelets no drive or stop line oriented, from their oriented neighbours (right-hand traffic:
  // lanelet/direction.cpp), round by round.
  for (int round = 0; round < kMaxPropagation; ++round) {
    const auto inferred = neighbourDirections(plan, map);
    if (inferred.empty()) break;
    for (const auto& [l, along] : inferred) {
      auto& ll = plan.lanelets[l];
      (along ? ll.votes_for : ll.votes_against) = 1;
      ++plan.lanelets_oriented_by_neighbours;
      orient(plan, ll);
    }
  }
  addConnectors(plan, drives, settings);
  return plan;
}

}  // namespace mapfuse::lanelet
