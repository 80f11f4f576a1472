#include "crossing_lines.hpp"

#include <algorithm>
#include <cmath>

namespace mapfuse::aggregate {
namespace {

// Unit directions of the segments the scan in piecesCross uses, by the same expressions so the
// values are bit-identical: a's segments of length >= 1e-9 (s / |s|), b's of squared length
// >= 1e-12 (s / sqrt(|s|^2)).
std::vector<Eigen::Vector2d> directionsOfA(const std::vector<Eigen::Vector2d>& a) {
  std::vector<Eigen::Vector2d> dirs;
  dirs.reserve(a.size());
  for (std::size_t k = 1; k < a.size(); ++k) {
    const Eigen::Vector2d s = a[k] - a[k - 1];
    const double len = s.norm();
    if (len >= 1e-9) dirs.push_back(s / len);
  }
  return dirs;
}
std::vector<Eigen::Vector2d> directionsOfB(const std::vector<Eigen::Vector2d>& b) {
  std::vector<Eigen::Vector2d> dirs;
  dirs.reserve(b.size());
  for (std::size_t k = 1; k < b.size(); ++k) {
    const Eigen::Vector2d s = b[k] - b[k - 1];
    const double len2 = s.squaredNorm();
    if (len2 >= 1e-12) dirs.push_back(s / std::sqrt(len2));
  }
  return dirs;
}

}  // namespace

bool piecesCross(const std::vector<Eigen::Vector2d>& a, const std::vector<Eigen::Vector2d>& b,
                 double near, double max_angle, double step) {
  if (a.size() < 2 || b.size() < 2) return false;
  const double cos_max = std::cos(max_angle);
  // Quick accept: a sample of a is counted crossing only when the direction of the segment of a
  // it lies on differs by more than max_angle from all of b's segments near it. When no segment
  // of a differs that much from any segment of b, no sample can, and the answer is false
  // whatever the distances: the scan below (O(samples of a x segments of b)) is skipped. Pieces
  // of one line (nearly all overlapping pairs) have a few near-parallel segments each, so this
  // costs O(vertices of a x vertices of b).
  {
    const auto da = directionsOfA(a), db = directionsOfB(b);
    bool any_apart = false;
    for (const auto& u : da) {
      for (const auto& w : db)
        if (std::abs(w.dot(u)) < cos_max) {
          any_apart = true;
          break;
        }
      if (any_apart) break;
    }
    if (!any_apart) return false;
  }
  int close = 0, crossing = 0;
  // p crosses when its direction differs by more than max_angle from every segment of b
  // within `near` (on a curve drawn with few vertices the nearest segment alone may be the
  // neighbour of the one p runs along)
  auto test = [&](const Eigen::Vector2d& p, const Eigen::Vector2d& dir) {
    bool any = false;
    double best_cos = -1.0;
    for (std::size_t k = 1; k < b.size(); ++k) {
      const Eigen::Vector2d s = b[k] - b[k - 1];
      const double len2 = s.squaredNorm();
      if (len2 < 1e-12) continue;
      const double t = std::clamp((p - b[k - 1]).dot(s) / len2, 0.0, 1.0);
      const double d = (b[k - 1] + t * s - p).norm();
      if (d > near) continue;
      any = true;
      best_cos = std::max(best_cos, std::abs((s / std::sqrt(len2)).dot(dir)));
    }
    if (!any) return;
    ++close;
    if (best_cos < cos_max) ++crossing;
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
