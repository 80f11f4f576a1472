#include "mapfuse/sim/polyline.hpp"

#include <algorithm>
#include <cmath>

namespace mapfuse::sim {

std::vector<double> arcLengths(const Polyline& line) {
  std::vector<double> s(line.size(), 0.0);
  for (std::size_t i = 1; i < line.size(); ++i) s[i] = s[i - 1] + (line[i] - line[i - 1]).norm();
  return s;
}

Eigen::Vector3d pointAt(const Polyline& line, const std::vector<double>& cumulative, double s) {
  if (line.size() == 1 || s <= 0.0) return line.front();
  if (s >= cumulative.back()) return line.back();
  const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), s);
  const std::size_t i = static_cast<std::size_t>(it - cumulative.begin());  // cumulative[i] > s
  const double seg = cumulative[i] - cumulative[i - 1];
  const double a = seg > 0.0 ? (s - cumulative[i - 1]) / seg : 0.0;
  return line[i - 1] + a * (line[i] - line[i - 1]);
}

Polyline subLine(const Polyline& line, double s0, double s1, double step) {
  return subLine(line, arcLengths(line), s0, s1, step);
}

Polyline subLine(const Polyline& line, const std::vector<double>& cum, double s0, double s1,
                 double step) {
  s0 = std::max(0.0, s0);
  s1 = std::min(cum.back(), s1);
  Polyline out;
  if (s1 <= s0) return out;
  const int n = std::max(1, static_cast<int>(std::ceil((s1 - s0) / step - 1e-9)));
  out.reserve(n + 1);
  for (int k = 0; k <= n; ++k) out.push_back(pointAt(line, cum, s0 + (s1 - s0) * k / n));
  return out;
}

Polyline resample(const Polyline& line, double step) {
  if (line.size() < 2) return line;
  return subLine(line, 0.0, arcLengths(line).back(), step);
}

Eigen::Vector3d leftNormalAt(const Polyline& line, std::size_t i) {
  const std::size_t a = i > 0 ? i - 1 : 0;
  const std::size_t b = std::min(line.size() - 1, i + 1);
  Eigen::Vector3d d = line[b] - line[a];
  d.z() = 0.0;
  const double n = d.norm();
  if (n < 1e-12) return Eigen::Vector3d(0, 1, 0);
  return Eigen::Vector3d(-d.y() / n, d.x() / n, 0.0);
}

Polyline offsetLine(const Polyline& line, double offset) {
  Polyline out(line.size());
  for (std::size_t i = 0; i < line.size(); ++i) out[i] = line[i] + offset * leftNormalAt(line, i);
  return out;
}

Polyline reversed(Polyline line) {
  std::reverse(line.begin(), line.end());
  return line;
}

Polyline smooth(const Polyline& line, int half_window, int passes) {
  Polyline cur = line;
  const int n = static_cast<int>(line.size());
  for (int p = 0; p < passes; ++p) {
    Polyline next = cur;
    for (int i = 1; i + 1 < n; ++i) {
      const int w = std::min({half_window, i, n - 1 - i});
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (int k = -w; k <= w; ++k) sum += cur[i + k];
      next[i] = sum / (2 * w + 1);
    }
    cur.swap(next);
  }
  return cur;
}

namespace {
double pointSegmentDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                            const Eigen::Vector3d& b) {
  const Eigen::Vector3d d = b - a;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (a + t * d - p).norm();
}
}  // namespace

double distanceToPolyline(const Polyline& line, const Eigen::Vector3d& p) {
  if (line.size() == 1) return (line[0] - p).norm();
  double best = 1e300;
  for (std::size_t i = 1; i < line.size(); ++i)
    best = std::min(best, pointSegmentDistance(p, line[i - 1], line[i]));
  return best;
}

double distanceToPolygonXY(const Polyline& ring, const Eigen::Vector3d& p) {
  bool inside = false;
  const std::size_t n = ring.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const auto& a = ring[i];
    const auto& b = ring[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      inside = !inside;
  }
  if (inside) return 0.0;
  double best = 1e300;
  const Eigen::Vector3d q(p.x(), p.y(), 0.0);
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Eigen::Vector3d a(ring[j].x(), ring[j].y(), 0.0), b(ring[i].x(), ring[i].y(), 0.0);
    best = std::min(best, pointSegmentDistance(q, a, b));
  }
  return best;
}

}  // namespace mapfuse::sim
