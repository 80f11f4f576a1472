#include "mapfuse/lidar/map_registration.hpp"

#include <cmath>
#include <limits>

namespace mapfuse::lidar {
namespace {

struct Normal {
  Matrix6d H = Matrix6d::Zero();
  Vector6d b = Vector6d::Zero();
  int n = 0;
  double sq = 0.0;
};

/// One Gauss-Newton system at T (kiss-icp eq. (10)-(11)), left perturbation. The residual is the
/// distance to the matched map point's surface, r = n^T (T p - q) with Jacobian n^T [I, -[T p]x]
/// (point-to-plane, Chen and Medioni 1992; n estimated in the scan the map point came from):
/// points slide along surfaces instead of sticking to where earlier sweeps' rings sampled them.
/// Map points without a normal are left out (with point_to_plane = false every correspondence is
/// point-to-point, T p - q). Geman-McClure weight w = k^2 / (k + r^2)^2.
Normal linearize(const LocalVoxelMap& map, const std::vector<Eigen::Vector3d>& source,
                 const Pose3& T, double max_d2, double kernel, bool point_to_plane) {
  Normal s;
  const double k2 = kernel * kernel;
  MapNeighbor nb;
  Eigen::Matrix<double, 3, 6> J;
  J.leftCols<3>().setIdentity();
  for (const Eigen::Vector3d& p : source) {
    const Eigen::Vector3d q = T * p;
    if (!map.nearest(q, max_d2, &nb)) continue;
    const Eigen::Vector3d r = q - nb.point;
    J.rightCols<3>() = -skew(q);
    if (point_to_plane && nb.normal.squaredNorm() > 0.5) {
      const double e = nb.normal.dot(r);
      const Eigen::Matrix<double, 1, 6> Jn = nb.normal.transpose() * J;
      const double w = k2 / ((kernel + e * e) * (kernel + e * e));
      s.H.noalias() += w * Jn.transpose() * Jn;
      s.b.noalias() += w * Jn.transpose() * e;
    } else if (point_to_plane) {
      continue;  // no surface known: a point-to-point pull would stick to the old samples
    } else {
      const double r2 = r.squaredNorm();
      const double w = k2 / ((kernel + r2) * (kernel + r2));
      s.H.noalias() += w * J.transpose() * J;
      s.b.noalias() += w * J.transpose() * r;
    }
    s.sq += nb.dist_sq;
    ++s.n;
  }
  return s;
}

}  // namespace

MapRegistrationResult registerToMap(const LocalVoxelMap& map,
                                    const std::vector<Eigen::Vector3d>& source, const Pose3& T_init,
                                    double max_distance, double kernel_scale,
                                    const MapRegistrationSettings& s) {
  MapRegistrationResult res;
  Pose3 T = T_init;
  const double max_d2 = max_distance * max_distance;
  double last_step = std::numeric_limits<double>::infinity();
  std::vector<Pose3> recent;  // poses of the last kRecent iterations
  constexpr std::size_t kRecent = 10;
  for (int it = 0; it < s.max_iterations; ++it) {
    const Normal sys = linearize(map, source, T, max_d2, kernel_scale, s.point_to_plane);
    res.iterations = it + 1;
    if (sys.n < s.min_correspondences) {
      last_step = std::numeric_limits<double>::infinity();
      break;
    }
    const Vector6d dx = sys.H.ldlt().solve(-sys.b);
    if (!dx.allFinite()) {
      last_step = std::numeric_limits<double>::infinity();
      break;
    }
    T = expSE3(dx) * T;
    last_step = dx.norm();
    if (last_step < s.convergence) break;
    if (recent.size() == kRecent) recent.erase(recent.begin());
    recent.push_back(T);
  }
  // Converged: the last update was below the tolerance; or, when the iterations ran out with
  // correspondences switching back and forth at the threshold, the last kRecent poses all lie
  // within oscillation_tolerance (m, and the same in rad / 10) of the final one.
  res.converged = last_step < s.convergence;
  if (!res.converged && std::isfinite(last_step) && recent.size() == kRecent) {
    bool settled = true;
    for (const Pose3& P : recent) {
      const Pose3 d = P.inverse() * T;
      settled = settled && d.translation().norm() <= s.oscillation_tolerance &&
                Eigen::AngleAxisd(d.linear()).angle() <= 0.1 * s.oscillation_tolerance;
    }
    res.converged = settled;
  }
  // Keep the rotation exactly orthonormal (the products above accumulate rounding).
  const Eigen::Quaterniond q(T.linear());
  T.linear() = q.normalized().toRotationMatrix();
  const Normal fin = linearize(map, source, T, max_d2, kernel_scale, s.point_to_plane);
  res.T_map_scan = T;
  res.correspondences = fin.n;
  res.inlier_share = source.empty() ? 0.0 : double(fin.n) / double(source.size());
  res.rmse = fin.n > 0 ? std::sqrt(fin.sq / fin.n) : 0.0;
  if (fin.n < s.min_correspondences) res.converged = false;
  return res;
}

}  // namespace mapfuse::lidar
