#include "line_buffer.hpp"

#include <cmath>

namespace mapfuse::aggregate {
namespace {
constexpr double kMaxTurnCos = 0.70710678118654752;   // cos 45 deg
constexpr double kMaxTotalTurn = 2.0943951023931957;  // 120 deg
Eigen::Vector2d left(const Eigen::Vector2d& d) {
  return {-d.y(), d.x()};
}
}  // namespace

std::optional<std::vector<Eigen::Vector2d>> mitreBuffer(const std::vector<Eigen::Vector2d>& line,
                                                        double width) {
  const std::size_t n = line.size();
  if (n < 2 || !(width > 0)) return std::nullopt;
  std::vector<Eigen::Vector2d> dir(n - 1);
  std::vector<double> len(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const Eigen::Vector2d d = line[i + 1] - line[i];
    len[i] = d.norm();
    if (!(len[i] > 1e-9)) return std::nullopt;
    dir[i] = d / len[i];
  }
  // Mitre vectors m (m . n_in = m . n_out = 1) and the length each inner corner cuts off its two
  // segments, w tan(theta / 2).
  std::vector<Eigen::Vector2d> mitre(n);
  std::vector<double> cut(n, 0.0);
  mitre[0] = left(dir[0]);
  mitre[n - 1] = left(dir[n - 2]);
  double turning = 0;
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double c = dir[i - 1].dot(dir[i]);
    if (c < kMaxTurnCos) return std::nullopt;
    const double s = dir[i - 1].x() * dir[i].y() - dir[i - 1].y() * dir[i].x();
    turning += std::atan2(std::abs(s), c);
    const Eigen::Vector2d a = left(dir[i - 1]), b = left(dir[i]);
    mitre[i] = (a + b) / (1.0 + a.dot(b));
    cut[i] = width * std::abs(s) / (1.0 + c);
  }
  if (turning > kMaxTotalTurn) return std::nullopt;
  for (std::size_t i = 0; i + 1 < n; ++i)
    if (cut[i] + cut[i + 1] >= len[i] - 1e-6) return std::nullopt;
  std::vector<Eigen::Vector2d> ring;
  ring.reserve(2 * n);
  for (std::size_t i = 0; i < n; ++i) ring.push_back(line[i] - width * mitre[i]);  // right side
  for (std::size_t i = n; i-- > 0;) ring.push_back(line[i] + width * mitre[i]);    // left, back
  return ring;
}

double ringArea(const std::vector<Eigen::Vector2d>& ring) {
  double a = 0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Eigen::Vector2d& p = ring[i];
    const Eigen::Vector2d& q = ring[(i + 1) % ring.size()];
    a += p.x() * q.y() - p.y() * q.x();
  }
  return 0.5 * std::abs(a);
}

}  // namespace mapfuse::aggregate
