#include "arc_link.hpp"

#include <Eigen/Dense>
#include <cmath>

namespace mapfuse::aggregate {

bool fitCircle2d(const std::vector<Eigen::Vector2d>& pts, Eigen::Vector2d* centre, double* radius) {
  if (pts.size() < 3) return false;
  // x^2 + y^2 + D x + E y + F = 0, linear in (D, E, F); centred for conditioning
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : pts) mean += p;
  mean /= double(pts.size());
  Eigen::MatrixXd A(pts.size(), 3);
  Eigen::VectorXd b(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Eigen::Vector2d q = pts[i] - mean;
    A.row(Eigen::Index(i)) << q.x(), q.y(), 1.0;
    b(Eigen::Index(i)) = -q.squaredNorm();
  }
  const Eigen::Matrix3d AtA = A.transpose() * A;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(AtA);         // ascending eigenvalues
  if (eig.eigenvalues()(0) < 1e-9 * eig.eigenvalues()(2)) return false;  // (nearly) collinear
  const Eigen::Vector3d x = AtA.ldlt().solve(A.transpose() * b);
  const Eigen::Vector2d c(-x(0) / 2, -x(1) / 2);
  const double r2 = c.squaredNorm() - x(2);
  if (!(r2 > 0) || !std::isfinite(r2)) return false;
  *centre = c + mean;
  *radius = std::sqrt(r2);
  return true;
}

namespace {

struct Arc {
  Eigen::Vector2d centre;
  double radius = 0;
  double sense = 1;  ///< +1 counter-clockwise from a's end towards b's end
};

// Signed angle at the centre from p to q, counter-clockwise positive, in (-pi, pi].
double angleFrom(const Arc& arc, const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
  const Eigen::Vector2d u = p.head<2>() - arc.centre, v = q.head<2>() - arc.centre;
  return std::atan2(u.x() * v.y() - u.y() * v.x(), u.dot(v));
}

bool fitTails(const std::vector<Eigen::Vector3d>& tail_a,
              const std::vector<Eigen::Vector3d>& tail_b, Arc* arc) {
  if (tail_a.size() < 2 || tail_b.size() < 2) return false;
  std::vector<Eigen::Vector2d> pts;
  for (const auto& p : tail_a) pts.push_back(p.head<2>());
  for (const auto& p : tail_b) pts.push_back(p.head<2>());
  if (!fitCircle2d(pts, &arc->centre, &arc->radius)) return false;
  arc->sense = angleFrom(*arc, tail_a.back(), tail_a.front()) < 0 ? 1.0 : -1.0;
  return true;
}

}  // namespace

bool continuesOnArc(const std::vector<Eigen::Vector3d>& tail_a,
                    const std::vector<Eigen::Vector3d>& tail_b, const ArcLinkLimits& limits) {
  Arc arc;
  if (!fitTails(tail_a, tail_b, &arc) || arc.radius < limits.min_radius) return false;
  for (const auto* tail : {&tail_a, &tail_b})
    for (const auto& p : *tail)
      if (std::abs((p.head<2>() - arc.centre).norm() - arc.radius) > limits.max_residual)
        return false;
  // angles travelled from a's end in a's direction of travel (inner point -> end)
  const double to_b = arc.sense * angleFrom(arc, tail_a.back(), tail_b.front());
  const double b_inner = arc.sense * angleFrom(arc, tail_a.back(), tail_b.back());
  return to_b * arc.radius >= -limits.max_residual && to_b * arc.radius <= limits.max_gap &&
         b_inner > to_b;
}

std::vector<Eigen::Vector3d> arcBridge(const std::vector<Eigen::Vector3d>& tail_a,
                                       const std::vector<Eigen::Vector3d>& tail_b, double step) {
  Arc arc;
  std::vector<Eigen::Vector3d> out;
  if (!fitTails(tail_a, tail_b, &arc)) return out;
  const Eigen::Vector3d &a = tail_a.back(), &b = tail_b.front();
  const double span = arc.sense * angleFrom(arc, a, b);
  const int n = int(std::floor(std::abs(span) * arc.radius / step));
  const Eigen::Vector2d ra = a.head<2>() - arc.centre;
  const double start = std::atan2(ra.y(), ra.x());
  for (int k = 1; k < n; ++k) {
    const double t = double(k) / n, phi = start + arc.sense * span * t;
    out.emplace_back(arc.centre.x() + arc.radius * std::cos(phi),
                     arc.centre.y() + arc.radius * std::sin(phi), (1 - t) * a.z() + t * b.z());
  }
  return out;
}

}  // namespace mapfuse::aggregate
