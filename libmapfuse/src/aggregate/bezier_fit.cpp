#include "bezier_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "mapfuse/io/vector_map_io.hpp"

namespace mapfuse::aggregate {
namespace {

using Vec3 = Eigen::Vector3d;

Vec3 derivative(const BezierSegment& b, double s) {
  const double u = 1.0 - s;
  return 3 * u * u * (b[1] - b[0]) + 6 * u * s * (b[2] - b[1]) + 3 * s * s * (b[3] - b[2]);
}

Vec3 secondDerivative(const BezierSegment& b, double s) {
  return 6 * (1 - s) * (b[2] - 2 * b[1] + b[0]) + 6 * s * (b[3] - 2 * b[2] + b[1]);
}

std::vector<double> chordParameters(const std::vector<Vec3>& p) {
  std::vector<double> u(p.size(), 0.0);
  for (std::size_t i = 1; i < p.size(); ++i) u[i] = u[i - 1] + (p[i] - p[i - 1]).norm();
  const double total = u.back();
  for (auto& v : u) v = total > 0 ? v / total : 0.0;
  return u;
}

// Unit direction from p[i] towards the point about `window` metres away (step +1 or -1).
Vec3 tangentAt(const std::vector<Vec3>& p, std::size_t i, int step, double window) {
  std::size_t j = i;
  double length = 0.0;
  while (length < window) {
    if (step > 0 && j + 1 >= p.size()) break;
    if (step < 0 && j == 0) break;
    const std::size_t k = step > 0 ? j + 1 : j - 1;
    length += (p[k] - p[j]).norm();
    j = k;
  }
  Vec3 t = p[j] - p[i];
  if (t.norm() < 1e-9) t = Vec3::UnitX() * double(step);
  return t.normalized();
}

struct Fitter {
  const std::vector<Vec3>& p;
  const BezierFitParams& params;
  std::vector<BezierSegment> chain;
  double max_dev = 0.0, sum_sq = 0.0;
  std::size_t count = 0;

  void fit(std::size_t a, std::size_t b, const Vec3& t0, const Vec3& t1) {
    std::vector<Vec3> q(p.begin() + a, p.begin() + b + 1);
    std::vector<double> u = chordParameters(q);
    const BezierSegment seg = fitCubicBezier(q, u, t0, t1, params.reparam_iterations);
    double worst = 0.0;
    std::size_t worst_i = 0;
    std::vector<double> err(q.size());
    for (std::size_t i = 0; i < q.size(); ++i) {
      err[i] = (io::bezierPoint(seg, u[i]) - q[i]).norm();
      if (err[i] > worst) worst = err[i], worst_i = i;
    }
    if (worst <= params.max_deviation || q.size() <= 2) {
      chain.push_back(seg);
      max_dev = std::max(max_dev, worst);
      for (double e : err) sum_sq += e * e;
      count += q.size();
      return;
    }
    // split at the worst point, kept away from the ends; G1 tangent there
    const std::size_t s = a + std::clamp<std::size_t>(worst_i, 1, q.size() - 2);
    const Vec3 ts =
        (tangentAt(p, s, +1, params.tangent_window) - tangentAt(p, s, -1, params.tangent_window))
            .normalized();
    fit(a, s, t0, -ts);
    fit(s, b, ts, t1);
  }
};

}  // namespace

BezierSegment fitCubicBezier(const std::vector<Vec3>& p, std::vector<double>& u, const Vec3& t0,
                             const Vec3& t1, int iterations) {
  const Vec3& P0 = p.front();
  const Vec3& P3 = p.back();
  const double chord = (P3 - P0).norm();
  BezierSegment seg{P0, P0 + t0 * chord / 3, P3 + t1 * chord / 3, P3};
  for (int it = 0; it <= iterations; ++it) {
    // eq. (15): least squares for the tangent magnitudes (a, b)
    Eigen::Matrix2d C = Eigen::Matrix2d::Zero();
    Eigen::Vector2d X = Eigen::Vector2d::Zero();
    for (std::size_t i = 0; i < p.size(); ++i) {
      const double s = u[i], r = 1 - s;
      const double b0 = r * r * r, b1 = 3 * r * r * s, b2 = 3 * r * s * s, b3 = s * s * s;
      const Vec3 A1 = t0 * b1, A2 = t1 * b2;
      C(0, 0) += A1.dot(A1);
      C(0, 1) += A1.dot(A2);
      C(1, 1) += A2.dot(A2);
      const Vec3 rest = p[i] - (b0 + b1) * P0 - (b2 + b3) * P3;
      X(0) += A1.dot(rest);
      X(1) += A2.dot(rest);
    }
    C(1, 0) = C(0, 1);
    double a = chord / 3, b = chord / 3;
    const double det = C.determinant();
    if (std::abs(det) > 1e-12) {
      const Eigen::Vector2d ab = C.inverse() * X;
      // Schneider's fallback when the solution degenerates: tiny or negative handles, or handles
      // longer than the chord (end tangents at odds with the data; the curve would swing metres
      // away from a short piece)
      if (ab(0) > 1e-3 * chord && ab(1) > 1e-3 * chord && ab(0) <= chord && ab(1) <= chord)
        a = ab(0), b = ab(1);
    }
    seg = {P0, P0 + a * t0, P3 + b * t1, P3};
    if (it == iterations) break;
    // Newton re-parametrisation: nearest point on the curve for each sample
    for (std::size_t i = 1; i + 1 < p.size(); ++i) {
      const Vec3 d = io::bezierPoint(seg, u[i]) - p[i];
      const Vec3 d1 = derivative(seg, u[i]);
      const double den = d1.dot(d1) + d.dot(secondDerivative(seg, u[i]));
      if (std::abs(den) > 1e-12) u[i] = std::clamp(u[i] - d.dot(d1) / den, 0.0, 1.0);
    }
  }
  return seg;
}

BezierFitResult fitBezierChain(const std::vector<Vec3>& points, const BezierFitParams& params) {
  BezierFitResult result;
  std::vector<Vec3> p;  // drop repeated points
  for (const auto& q : points)
    if (p.empty() || (q - p.back()).norm() > 1e-6) p.push_back(q);
  if (p.size() < 2) return result;
  if (p.size() == 2) {
    const Vec3 d = (p[1] - p[0]) / 3;
    result.chain.push_back({p[0], p[0] + d, p[1] - d, p[1]});
    return result;
  }
  Fitter f{p, params, {}, 0.0, 0.0, 0};
  f.fit(0, p.size() - 1, tangentAt(p, 0, +1, params.tangent_window),
        tangentAt(p, p.size() - 1, -1, params.tangent_window));
  result.chain = std::move(f.chain);
  result.max_deviation = f.max_dev;
  result.rms_deviation = f.count ? std::sqrt(f.sum_sq / double(f.count)) : 0.0;
  return result;
}

MapInstance fittedLaneLine(const std::vector<Eigen::Vector3d>& centreline,
                           const AggregatorParams& params, AggregatorStats& stats, double& sum_sq,
                           std::size_t& count) {
  MapInstance inst;
  inst.cls = CrowdClass::kLaneLine;
  const BezierFitResult fit = fitBezierChain(centreline, params.bezier);  // eq. (15)
  inst.bezier = fit.chain;
  inst.points = io::sampleBezierChain(fit.chain, params.sample_step);
  stats.bezier_segments += fit.chain.size();
  stats.bezier_max_deviation = std::max(stats.bezier_max_deviation, fit.max_deviation);
  sum_sq += fit.rms_deviation * fit.rms_deviation * double(centreline.size());
  count += centreline.size();
  return inst;
}

}  // namespace mapfuse::aggregate
