#include "crossing_lines.hpp"

#include <algorithm>
#include <cmath>

namespace mapfuse::aggregate {

bool piecesCross(const std::vector<Eigen::Vector2d>& a, const std::vector<Eigen::Vector2d>& b,
                 double near, double max_angle, double step) {
  if (a.size() < 2 || b.size() < 2) return false;
  const double cos_max = std::cos(max_angle);
  int close = 0, crossing = 0;
  auto test = [&](const Eigen::Vector2d& p, const Eigen::Vector2d& dir) {
    double best = near;
    Eigen::Vector2d best_dir = Eigen::Vector2d::Zero();
    for (std::size_t k = 1; k < b.size(); ++k) {
      const Eigen::Vector2d s = b[k] - b[k - 1];
      const double len2 = s.squaredNorm();
      if (len2 < 1e-12) continue;
      const double t = std::clamp((p - b[k - 1]).dot(s) / len2, 0.0, 1.0);
      const double d = (b[k - 1] + t * s - p).norm();
      if (d <= best) best = d, best_dir = s / std::sqrt(len2);
    }
    if (best_dir.squaredNorm() == 0.0) return;
    ++close;
    if (std::abs(best_dir.dot(dir)) < cos_max) ++crossing;
  };
  for (std::size_t k = 1; k < a.size(); ++k) {
    const Eigen::Vector2d s = a[k] - a[k - 1];
    const double len = s.norm();
    if (len < 1e-9) continue;
    const Eigen::Vector2d dir = s / len;
    const int n = std::max(1, int(std::ceil(len / step)));
    for (int i = (k == 1 ? 0 : 1); i <= n; ++i) test(a[k - 1] + s * (double(i) / n), dir);
  }
  return close > 0 && 2 * crossing > close;
}

}  // namespace mapfuse::aggregate
