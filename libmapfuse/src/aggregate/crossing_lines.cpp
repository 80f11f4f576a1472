#include "crossing_lines.hpp"

#include <algorithm>
#include <cmath>

namespace mapfuse::aggregate {
namespace {

// A segment's unit direction, by the same expressions as piecesCross's scan so the values are
// bit-identical (a: s / |s| for |s| >= 1e-9; b: s / sqrt(|s|^2) for |s|^2 >= 1e-12), and its
// bounding box.
struct Segment {
  Eigen::Vector2d dir, lo, hi;
};
std::vector<Segment> segmentsOf(const std::vector<Eigen::Vector2d>& line, bool as_b) {
  std::vector<Segment> out;
  out.reserve(line.size());
  for (std::size_t k = 1; k < line.size(); ++k) {
    const Eigen::Vector2d s = line[k] - line[k - 1];
    Eigen::Vector2d dir;
    if (as_b) {
      const double len2 = s.squaredNorm();
      if (len2 < 1e-12) continue;
      dir = s / std::sqrt(len2);
    } else {
      const double len = s.norm();
      if (len < 1e-9) continue;
      dir = s / len;
    }
    out.push_back({dir, line[k].cwiseMin(line[k - 1]), line[k].cwiseMax(line[k - 1])});
  }
  return out;
}

}  // namespace

bool piecesCross(const std::vector<Eigen::Vector2d>& a, const std::vector<Eigen::Vector2d>& b,
                 double near, double max_angle, double step) {
  if (a.size() < 2 || b.size() < 2) return false;
  const double cos_max = std::cos(max_angle);
  // Quick accept: a sample of a is counted crossing only when the direction of the segment of a
  // it lies on differs by more than max_angle from all of b's segments near it, so from at
  // least one segment of b whose box comes within `near` of that segment's box. When no such
  // pair differs that much, no sample can, and the answer is false whatever the distances: the
  // scan below (O(samples of a x segments of b)) is skipped. Pieces of one line (nearly all
  // overlapping pairs, curved ones too: only segments side by side are compared) pass here, at
  // O(vertices of a x vertices of b).
  {
    const double reach = near + 1e-6;  // m: samples and distances are exact up to rounding
    const auto sa = segmentsOf(a, false), sb = segmentsOf(b, true);
    bool any_apart = false;
    for (const auto& u : sa) {
      for (const auto& w : sb)
        if (w.lo.x() <= u.hi.x() + reach && u.lo.x() <= w.hi.x() + reach &&
            w.lo.y() <= u.hi.y() + reach && u.lo.y() <= w.hi.y() + reach &&
            std::abs(w.dir.dot(u.dir)) < cos_max) {
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
