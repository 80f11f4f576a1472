#include "stop_line_merge.hpp"

#include <algorithm>
#include <numeric>

#include "mapfuse/aggregate/geometry2d.hpp"

namespace mapfuse::aggregate::detail {
namespace {
constexpr double kEndBand = 0.5;      // m: ends this far inside the outer ones are pieces' ends
constexpr double kEndQuantile = 0.2;  // outer ends: this weighted quantile of the ends

// Weighted quantile q of values v.
double quantile(const std::vector<double>& v, const std::vector<double>& w, double q) {
  std::vector<std::size_t> order(v.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return v[a] < v[b]; });
  const double total = std::accumulate(w.begin(), w.end(), 0.0);
  double acc = 0;
  for (std::size_t k : order) {
    acc += w[k];
    if (acc >= q * total) return v[k];
  }
  return v[order.back()];
}
}  // namespace

double stopLineDistance(const Segment& a, const Segment& b) {
  const Eigen::Vector3d ma = 0.5 * (a[0] + a[1]), mb = 0.5 * (b[0] + b[1]);
  return std::min(distanceToSegment2d(ma, b[0], b[1]), distanceToSegment2d(mb, a[0], a[1]));
}

Segment mergeStopLines(const std::vector<Segment>& members, const std::vector<double>& w,
                       std::size_t ref) {
  const Eigen::Vector2d ref_dir = (members[ref][1] - members[ref][0]).head<2>().normalized();
  const Eigen::Vector3d origin = 0.5 * (members[ref][0] + members[ref][1]);
  // members oriented like the reference; weighted mean direction
  std::vector<Segment> seg(members);
  Eigen::Vector2d dir = Eigen::Vector2d::Zero();
  double wsum = 0;
  for (std::size_t i = 0; i < seg.size(); ++i) {
    if ((seg[i][1] - seg[i][0]).head<2>().dot(ref_dir) < 0) std::swap(seg[i][0], seg[i][1]);
    dir += w[i] * (seg[i][1] - seg[i][0]).head<2>().normalized();
    wsum += w[i];
  }
  const Eigen::Vector2d u = dir.normalized(), nrm(-u.y(), u.x());
  std::vector<double> s0(seg.size()), s1(seg.size());
  double lateral = 0, z = 0;
  for (std::size_t i = 0; i < seg.size(); ++i) {
    s0[i] = (seg[i][0] - origin).head<2>().dot(u);
    s1[i] = (seg[i][1] - origin).head<2>().dot(u);
    lateral += w[i] * (0.5 * (seg[i][0] + seg[i][1]) - origin).head<2>().dot(nrm);
    z += w[i] * 0.5 * (seg[i][0].z() + seg[i][1].z());
  }
  lateral /= wsum;
  z /= wsum;
  const double q0 = quantile(s0, w, kEndQuantile);
  std::vector<double> neg1(s1.size());
  for (std::size_t i = 0; i < s1.size(); ++i) neg1[i] = -s1[i];
  const double q1 = -quantile(neg1, w, kEndQuantile);
  double e0 = 0, w0 = 0, e1 = 0, w1 = 0;
  for (std::size_t i = 0; i < seg.size(); ++i) {
    if (s0[i] <= q0 + kEndBand) e0 += w[i] * s0[i], w0 += w[i];
    if (s1[i] >= q1 - kEndBand) e1 += w[i] * s1[i], w1 += w[i];
  }
  auto at = [&](double s) {
    const Eigen::Vector2d p = origin.head<2>() + s * u + lateral * nrm;
    return Eigen::Vector3d(p.x(), p.y(), z);
  };
  return {at(e0 / w0), at(e1 / w1)};
}

}  // namespace mapfuse::aggregate::detail
