#include "discrete_merge.hpp"

// Boost.Geometry instantiations trigger GCC false positives.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <boost/geometry.hpp>
#include <boost/geometry/geometries/box.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/index/rtree.hpp>
#include <cmath>
#include <map>
#include <set>

#include "mapfuse/aggregate/dbscan.hpp"
#include "partner_drives.hpp"
#include "stop_line_merge.hpp"

namespace mapfuse::aggregate {
using detail::partnerDrives;
using detail::stopLineDistance;
namespace {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;
using Vec3 = Eigen::Vector3d;
using P2 = bg::model::d2::point_xy<double>;
using Poly2 = bg::model::polygon<P2>;
using MPoly2 = bg::model::multi_polygon<Poly2>;
using Box2 = bg::model::box<P2>;
using BoxValue = std::pair<Box2, std::size_t>;

Poly2 toPolygon(const std::vector<Vec3>& pts) {
  Poly2 poly;
  for (const auto& p : pts) poly.outer().emplace_back(p.x(), p.y());
  bg::correct(poly);  // closes the ring and fixes the orientation
  Poly2 hull;
  bg::convex_hull(poly, hull);  // robust against self-intersecting corner orders
  return hull;
}

Box2 boxAround(const std::vector<Vec3>& pts, double margin) {
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (const auto& p : pts) {
    x0 = std::min(x0, p.x()), y0 = std::min(y0, p.y());
    x1 = std::max(x1, p.x()), y1 = std::max(y1, p.y());
  }
  return Box2(P2(x0 - margin, y0 - margin), P2(x1 + margin, y1 + margin));
}

Vec3 mean(const std::vector<Vec3>& pts) {
  Vec3 m = Vec3::Zero();
  for (const auto& p : pts) m += p;
  return pts.empty() ? m : Vec3(m / double(pts.size()));
}

// Member corners re-ordered (cyclic shift, optional reversal) to best match `ref`.
std::vector<Vec3> alignCorners(const std::vector<Vec3>& ref, const std::vector<Vec3>& c) {
  const std::size_t k = ref.size();
  double best = 1e300;
  std::vector<Vec3> out = c;
  for (int rev = 0; rev < 2; ++rev)
    for (std::size_t s = 0; s < k; ++s) {
      std::vector<Vec3> cand(k);
      for (std::size_t i = 0; i < k; ++i) cand[i] = rev ? c[(s + k - i) % k] : c[(s + i) % k];
      double cost = 0;
      for (std::size_t i = 0; i < k; ++i) cost += (cand[i] - ref[i]).squaredNorm();
      if (cost < best) best = cost, out = cand;
    }
  return out;
}

template <class T>
T majority(const std::map<T, double>& votes, T fallback) {
  double best = -1;
  for (const auto& [value, w] : votes)
    if (w > best) best = w, fallback = value;
  return fallback;
}

}  // namespace

std::vector<Vec3> toRectangle(const std::vector<Vec3>& points) {
  if (points.size() == 4) return points;
  const Vec3 m = mean(points);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& p : points) cov += (p - m) * (p - m).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
  const Vec3 u = es.eigenvectors().col(2), v = es.eigenvectors().col(1);
  double a0 = 1e300, a1 = -1e300, b0 = 1e300, b1 = -1e300;
  for (const auto& p : points) {
    a0 = std::min(a0, (p - m).dot(u)), a1 = std::max(a1, (p - m).dot(u));
    b0 = std::min(b0, (p - m).dot(v)), b1 = std::max(b1, (p - m).dot(v));
  }
  return {m + a0 * u + b0 * v, m + a1 * u + b0 * v, m + a1 * u + b1 * v, m + a0 * u + b1 * v};
}

double polygonIou2d(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  const Poly2 pa = toPolygon(a), pb = toPolygon(b);
  MPoly2 inter;
  bg::intersection(pa, pb, inter);
  const double i = bg::area(inter);
  const double u = bg::area(pa) + bg::area(pb) - i;
  return u > 0 ? i / u : 0.0;
}

namespace {
/// One observation's geometry as the clustering compares it: a planar element's polygon, a stop
/// line's end points, a point element's base; and its centre.
struct DiscreteGeometry {
  std::vector<std::vector<Vec3>> geom;
  std::vector<Vec3> centre;
};

DiscreteGeometry representativeGeometry(const std::vector<Observation>& items,
                                        const std::vector<std::size_t>& indices, CrowdClass cls) {
  const std::size_t n = indices.size();
  const GeometryKind kind = geometryKind(cls);
  DiscreteGeometry g{std::vector<std::vector<Vec3>>(n), std::vector<Vec3>(n)};
  for (std::size_t i = 0; i < n; ++i) {
    const auto& pts = items[indices[i]].points;
    if (kind == GeometryKind::kPlanar)  // polygons keep their own vertices (arrows are not boxes)
      g.geom[i] = pts.size() >= 3 ? pts : toRectangle(pts);
    else if (cls == CrowdClass::kStopLine)
      g.geom[i] = {pts.front(), pts.back()};
    else
      g.geom[i] = {pts.front()};
    g.centre[i] = mean(g.geom[i]);
  }
  return g;
}

/// DBSCAN's eps-neighbourhoods (symmetric, sorted): arrows and crosswalks by IoU, stop lines by
/// midpoint distance and direction, signs, poles and lights by 3D distance; each observation is
/// compared with the candidates of at most `partner_drives` other drives (partner_drives.hpp).
std::vector<std::vector<std::size_t>> discreteNeighbours(const std::vector<Observation>& items,
                                                         const std::vector<std::size_t>& indices,
                                                         CrowdClass cls, const DiscreteGeometry& g,
                                                         const DiscreteMergeParams& p,
                                                         int partner_drives) {
  const std::size_t n = indices.size();
  const auto& geom = g.geom;
  const auto& centre = g.centre;
  const bool by_iou = cls == CrowdClass::kGroundArrow || cls == CrowdClass::kCrosswalk;
  const bool stop_line = cls == CrowdClass::kStopLine;
  const double radius = stop_line                         ? p.stop_line_radius
                        : cls == CrowdClass::kTrafficSign ? p.sign_radius
                                                          : p.point_radius;
  std::vector<BoxValue> boxes(n);
  for (std::size_t i = 0; i < n; ++i)
    boxes[i] = {by_iou      ? boxAround(geom[i], 0.0)
                : stop_line ? boxAround(geom[i], radius)  // a piece's midpoint on the segment
                            : boxAround({centre[i]}, radius),
                i};
  const bgi::rtree<BoxValue, bgi::rstar<16>> tree(boxes.begin(), boxes.end());
  const double cos_max = std::cos(p.stop_line_angle_deg * M_PI / 180.0);
  auto driveOf = [&](std::size_t i) { return items[indices[i]].drive; };
  std::vector<std::vector<std::size_t>> tested(n);
#pragma omp parallel
  {
    std::vector<BoxValue> hits;
    std::vector<int> present, partners;
#pragma omp for schedule(dynamic, 32)
    for (std::ptrdiff_t si = 0; si < std::ptrdiff_t(n); ++si) {
      const std::size_t i = std::size_t(si);
      hits.clear();
      tree.query(bgi::intersects(boxes[i].first), std::back_inserter(hits));
      present.clear();
      for (const auto& h : hits) present.push_back(driveOf(h.second));
      std::sort(present.begin(), present.end());
      present.erase(std::unique(present.begin(), present.end()), present.end());
      partnerDrives(present, driveOf(i), partner_drives,
                    uint64_t(driveOf(i)) + uint64_t(i) * 40503ull, partners);
      for (const auto& h : hits) {
        const std::size_t j = h.second;
        if (j == i || !std::binary_search(partners.begin(), partners.end(), driveOf(j))) continue;
        bool near = false;
        if (by_iou) {
          near = polygonIou2d(geom[i], geom[j]) >= p.min_iou;
        } else {
          near = stop_line ? stopLineDistance({geom[i][0], geom[i][1]}, {geom[j][0], geom[j][1]}) <=
                                 radius
                           : (centre[i] - centre[j]).norm() <= radius;
          if (near && stop_line) {
            const Vec3 di = (geom[i][1] - geom[i][0]).normalized();
            const Vec3 dj = (geom[j][1] - geom[j][0]).normalized();
            near = std::abs(di.dot(dj)) >= cos_max;
          }
        }
        if (near) tested[i].push_back(j);
      }
    }
  }
  std::vector<std::vector<std::size_t>> neighbours(n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j : tested[i]) {
      neighbours[i].push_back(j);
      neighbours[j].push_back(i);
    }
  for (auto& l : neighbours) {
    std::sort(l.begin(), l.end());
    l.erase(std::unique(l.begin(), l.end()), l.end());
  }
  return neighbours;
}

/// One cluster's instance: confidence-weighted mean of the members' geometry (vertices aligned
/// to the most confident member), stop lines merged from whole and partial pieces, the majority
/// style and colour, the support.
MapInstance mergeCluster(const std::vector<Observation>& items,
                         const std::vector<std::size_t>& indices, CrowdClass cls,
                         const DiscreteGeometry& g, const std::vector<std::size_t>& mem) {
  const auto& geom = g.geom;
  // reference member: highest confidence (lowest index on ties)
  std::size_t ref = mem.front();
  for (std::size_t i : mem)
    if (items[indices[i]].confidence > items[indices[ref]].confidence) ref = i;
  std::vector<Vec3> acc(geom[ref].size(), Vec3::Zero());
  double wsum = 0, height = 0;
  std::set<int> drives;
  std::map<LineStyle, double> styles;
  std::map<LineColor, double> colors;
  MapInstance inst;
  inst.cls = cls;
  for (std::size_t i : mem) {
    const Observation& o = items[indices[i]];
    const double w = std::max(o.confidence, 1e-3);  // confidence-weighted averaging
    drives.insert(o.drive);
    inst.support.observations += o.observations;
    styles[o.attributes.style] += w;
    colors[o.attributes.color] += w;
    // geometry: members with the reference's vertex count, vertices aligned then averaged
    if (geom[i].size() != acc.size()) continue;
    const std::vector<Vec3> gi = acc.size() > 1 ? alignCorners(geom[ref], geom[i]) : geom[i];
    for (std::size_t k = 0; k < acc.size(); ++k) acc[k] += w * gi[k];
    height += w * o.height;
    wsum += w;
  }
  for (auto& c : acc) c /= wsum;
  inst.points = acc;
  if (cls == CrowdClass::kStopLine) {  // whole and partial observations (stop_line_merge.hpp)
    std::vector<detail::Segment> segs;
    std::vector<double> ws;
    std::size_t r = 0;
    for (std::size_t i : mem) {
      if (i == ref) r = segs.size();
      segs.push_back({geom[i][0], geom[i][1]});
      ws.push_back(std::max(items[indices[i]].confidence, 1e-3));
    }
    const detail::Segment m = detail::mergeStopLines(segs, ws, r);
    inst.points = {m[0], m[1]};
  }
  if (geometryKind(cls) == GeometryKind::kPoint) inst.height = height / wsum;
  inst.support.drives = int(drives.size());
  inst.attributes.style = majority(styles, LineStyle::kNone);
  inst.attributes.color = majority(colors, LineColor::kNone);
  return inst;
}
}  // namespace

std::vector<MapInstance> mergeDiscrete(const std::vector<Observation>& items,
                                       const std::vector<std::size_t>& indices, CrowdClass cls,
                                       const DiscreteMergeParams& p, int num_drives,
                                       int partner_drives, std::size_t* noise) {
  const DiscreteGeometry g = representativeGeometry(items, indices, cls);
  const auto neighbours = discreteNeighbours(items, indices, cls, g, p, partner_drives);
  const int min_pts = std::max(1, std::min(p.min_pts, num_drives));
  const DbscanResult clusters = dbscan(neighbours, min_pts);
  if (noise) *noise = std::size_t(clusters.num_noise);
  std::vector<std::vector<std::size_t>> members(std::size_t(clusters.num_clusters));
  for (std::size_t i = 0; i < indices.size(); ++i)
    if (clusters.labels[i] >= 0) members[std::size_t(clusters.labels[i])].push_back(i);
  std::vector<MapInstance> out;
  out.reserve(members.size());
  for (const auto& mem : members) out.push_back(mergeCluster(items, indices, cls, g, mem));
  return out;
}

}  // namespace mapfuse::aggregate
