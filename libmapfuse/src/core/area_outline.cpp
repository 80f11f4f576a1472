#include "mapfuse/core/area_outline.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace mapfuse {
namespace {
using Vec3 = Eigen::Vector3d;

/// A hull whose four-vertex simplification covers at most this much more than its three-vertex
/// one is a triangle (a whole parallelogram covers twice its three corners' triangle).
constexpr double kTriangleAreaRatio = 1.25;

double cross(const Vec3& o, const Vec3& a, const Vec3& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

double ringAreaXy(const std::vector<Vec3>& r) {
  double a = 0.0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Vec3 &p = r[i], &q = r[(i + 1) % r.size()];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * std::abs(a);
}
}  // namespace

std::vector<Vec3> convexHullXy(const std::vector<Vec3>& points) {
  std::vector<Vec3> p = points;
  std::sort(p.begin(), p.end(), [](const Vec3& a, const Vec3& b) {
    return a.x() != b.x() ? a.x() < b.x() : a.y() < b.y();
  });
  if (p.size() < 3) return p;
  std::vector<Vec3> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {  // lower hull
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i > 0; --i) {  // upper hull
    while (k >= t && cross(h[k - 2], h[k - 1], p[i - 1]) <= 0) --k;
    h[k++] = p[i - 1];
  }
  h.resize(k - 1);  // the last point repeats the first
  return h;
}

std::vector<Vec3> simplifyRing(std::vector<Vec3> ring, std::size_t max_vertices) {
  max_vertices = std::max<std::size_t>(3, max_vertices);
  while (ring.size() > max_vertices) {
    const std::size_t n = ring.size();
    std::size_t worst = 0;
    double least = 1e300;
    for (std::size_t i = 0; i < n; ++i) {
      const double a = std::abs(cross(ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]));
      if (a < least) least = a, worst = i;
    }
    ring.erase(ring.begin() + std::ptrdiff_t(worst));
  }
  return ring;
}

std::vector<Vec3> alignRing(const std::vector<Vec3>& ref, const std::vector<Vec3>& c) {
  const std::size_t k = ref.size();
  double best = 1e300;
  std::vector<Vec3> out = c, cand(k);
  for (int rev = 0; rev < 2; ++rev)
    for (std::size_t s = 0; s < k; ++s) {
      double cost = 0;
      for (std::size_t i = 0; i < k; ++i) {
        cand[i] = rev ? c[(s + k - i) % k] : c[(s + i) % k];
        cost += (cand[i] - ref[i]).squaredNorm();
      }
      if (cost < best) best = cost, out = cand;
    }
  return out;
}

std::vector<Vec3> completeParallelogram(const std::vector<Vec3>& tri) {
  if (tri.size() != 3) return tri;
  // the corner between the two seen sides: the widest angle of the triangle
  std::size_t b = 0;
  double widest = -1.0;
  for (std::size_t i = 0; i < 3; ++i) {
    const Vec3 u = (tri[(i + 2) % 3] - tri[i]).normalized(),
               w = (tri[(i + 1) % 3] - tri[i]).normalized();
    const double angle = std::acos(std::clamp(u.head<2>().dot(w.head<2>()), -1.0, 1.0));
    if (angle > widest) widest = angle, b = i;
  }
  const Vec3 &a = tri[(b + 2) % 3], &mid = tri[b], &c = tri[(b + 1) % 3];
  return {a, mid, c, a + c - mid};  // the ring order kept: a, b, c, then the corner opposite b
}

std::vector<Vec3> areaOutline(const std::vector<std::vector<Vec3>>& rings, int min_complete,
                              std::size_t max_vertices, double max_corner_spread,
                              std::size_t corner_count) {
  std::map<std::size_t, int> counts;
  for (const auto& r : rings)
    if (r.size() >= 3 && (corner_count == 0 || r.size() == corner_count)) ++counts[r.size()];
  std::size_t mode = 0;
  int most = 0;
  for (const auto& [size, n] : counts)
    if (n >= most) most = n, mode = size;  // ties: the larger count (more of the outline seen)
  if (mode >= 3 && most >= std::max(1, min_complete)) {
    // Vertex-wise mean of the complete observations, aligned to the first one.
    const std::vector<Vec3>* ref = nullptr;
    std::vector<std::vector<Vec3>> aligned;
    std::vector<Vec3> sum(mode, Vec3::Zero());
    for (const auto& r : rings) {
      if (r.size() != mode) continue;
      if (!ref) ref = &r;
      aligned.push_back(alignRing(*ref, r));
      for (std::size_t i = 0; i < mode; ++i) sum[i] += aligned.back()[i];
    }
    for (auto& v : sum) v /= double(most);
    // Corner lists agree vertex by vertex; hulls of partial views that happen to share a vertex
    // count do not (their vertices lie anywhere along the edges): those take the hull below.
    std::vector<double> spread;
    for (const auto& a : aligned) {
      double worst = 0.0;
      for (std::size_t i = 0; i < mode; ++i) worst = std::max(worst, (a[i] - sum[i]).norm());
      spread.push_back(worst);
    }
    std::nth_element(spread.begin(), spread.begin() + spread.size() / 2, spread.end());
    if (spread[spread.size() / 2] <= max_corner_spread) return sum;
  }
  std::vector<Vec3> all;
  for (const auto& r : rings) all.insert(all.end(), r.begin(), r.end());
  const std::vector<Vec3> hull = convexHullXy(all);
  std::vector<Vec3> outline = simplifyRing(hull, max_vertices);
  if (corner_count == 4 && hull.size() >= 3) {
    // A parallelogram of which one corner was never ranged (out of the view or the range band):
    // the hull is a triangle, or a quadrilateral whose fourth vertex adds next to no area. The
    // three seen corners fix the fourth (a minimum-area rectangle did this for right angles).
    std::vector<Vec3> tri = simplifyRing(hull, 3);
    if (ringAreaXy(outline) <= kTriangleAreaRatio * ringAreaXy(tri)) {
      // each corner: the mean of the points nearest to it (the hull's extreme points lie
      // outside the noisy clusters of observed corners)
      std::vector<Vec3> sum(3, Vec3::Zero());
      std::vector<int> count(3, 0);
      for (const auto& p : all) {
        std::size_t k = 0;
        for (std::size_t j = 1; j < 3; ++j)
          if ((p - tri[j]).head<2>().norm() < (p - tri[k]).head<2>().norm()) k = j;
        sum[k] += p, ++count[k];
      }
      for (std::size_t j = 0; j < 3; ++j) tri[j] = sum[j] / double(std::max(1, count[j]));
      outline = completeParallelogram(tri);
    }
  }
  return outline;
}

}  // namespace mapfuse
