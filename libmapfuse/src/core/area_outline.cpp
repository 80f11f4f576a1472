#include "mapfuse/core/area_outline.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace mapfuse {
namespace {
using Vec3 = Eigen::Vector3d;

double cross(const Vec3& o, const Vec3& a, const Vec3& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
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

std::vector<Vec3> areaOutline(const std::vector<std::vector<Vec3>>& rings, int min_complete,
                              std::size_t max_vertices, double max_corner_spread) {
  std::map<std::size_t, int> counts;
  for (const auto& r : rings)
    if (r.size() >= 3) ++counts[r.size()];
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
  return simplifyRing(convexHullXy(all), max_vertices);
}

}  // namespace mapfuse
