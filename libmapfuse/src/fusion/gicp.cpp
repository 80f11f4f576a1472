#include "mapfuse/fusion/gicp.hpp"

#include <omp.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "mapfuse/core/error.hpp"

namespace mapfuse::fusion {

GicpTarget::GicpTarget(Cloud cloud, double index_voxel_size) : cloud_(std::move(cloud)) {
  if (cloud_.covariances.empty()) estimateCovariances(cloud_);
  all_ = VoxelIndex(cloud_.points, index_voxel_size);
  if (cloud_.labels.empty()) return;
  int max_label = 0;
  for (uint8_t l : cloud_.labels) max_label = std::max<int>(max_label, l);
  label_members_.resize(max_label + 1);
  for (std::size_t i = 0; i < cloud_.size(); ++i)
    label_members_[cloud_.labels[i]].push_back(int(i));
  per_label_.resize(max_label + 1);
  for (int l = 0; l <= max_label; ++l) {
    if (label_members_[l].empty()) continue;
    std::vector<Eigen::Vector3d> pts;
    pts.reserve(label_members_[l].size());
    for (int i : label_members_[l]) pts.push_back(cloud_.points[i]);
    per_label_[l] = std::make_unique<VoxelIndex>(pts, index_voxel_size);
  }
}

int GicpTarget::nearest(const Eigen::Vector3d& q, int label, double max_dist_sq,
                        double* dist_sq) const {
  if (label < 0) return all_.nearest(q, max_dist_sq, dist_sq);
  if (label >= int(per_label_.size()) || !per_label_[label]) return -1;
  const int j = per_label_[label]->nearest(q, max_dist_sq, dist_sq);
  return j < 0 ? -1 : label_members_[label][j];
}

namespace {

struct Linearization {
  Matrix6d H = Matrix6d::Zero();
  Vector6d b = Vector6d::Zero();
  double cost = 0.0;
  double sq_sum = 0.0;  // Euclidean squared residuals of inliers
  int inliers = 0;
};

double labelValue(const std::vector<double>& v, int label, double fallback) {
  return (label >= 0 && label < int(v.size())) ? v[label] : fallback;
}

Linearization linearize(const GicpTarget& target, const Cloud& source, const Pose3& T,
                        const GicpSettings& s) {
  const Cloud& tc = target.cloud();
  const Eigen::Matrix3d R = T.linear();
  const double max_d2 = s.max_correspondence_distance * s.max_correspondence_distance;
  const bool use_labels = s.same_label_only;
  const int n = int(source.size());
  const int threads = std::max(1, s.num_threads);
  std::vector<Linearization> parts(threads);
#pragma omp parallel num_threads(threads)
  {
    Linearization& acc = parts[omp_get_thread_num()];
#pragma omp for schedule(static)
    for (int i = 0; i < n; ++i) {
      const int label = source.labels.empty() ? -1 : int(source.labels[i]);
      const double w_l = labelValue(s.label_weights, label, 1.0);
      if (w_l <= 0.0) continue;
      const Eigen::Vector3d& ps = source.points[i];
      const Eigen::Vector3d q = T * ps;
      double d2 = 0.0;
      const int j = target.nearest(q, use_labels ? label : -1, max_d2, &d2);
      if (j < 0) continue;
      const Eigen::Vector3d r = tc.points[j] - q;
      Eigen::Matrix3d M = Eigen::Matrix3d::Identity();
      if (!s.point_to_point)
        M = (tc.covariances[j] + R * source.covariances[i] * R.transpose()).inverse();
      const double m2 = r.dot(M * r);
      double w = w_l;
      const double delta = labelValue(s.label_huber_delta, label, s.huber_delta);
      double rho = m2;
      if (delta > 0.0) {
        const double m = std::sqrt(m2);
        if (m > delta) {
          w *= delta / m;
          rho = 2.0 * delta * m - delta * delta;
        }
      }
      // dr/dxi for T <- T exp(xi): [-R, R [s]x]
      Eigen::Matrix<double, 3, 6> J;
      J.leftCols<3>() = -R;
      J.rightCols<3>() = R * skew(ps);
      const Eigen::Matrix<double, 6, 3> JtM = J.transpose() * M;
      acc.H.noalias() += w * JtM * J;
      acc.b.noalias() += w * JtM * r;
      acc.cost += w_l * rho;
      acc.sq_sum += d2;
      ++acc.inliers;
    }
  }
  Linearization total;  // summed in thread order: deterministic for a fixed thread count
  for (const auto& p : parts) {
    total.H += p.H;
    total.b += p.b;
    total.cost += p.cost;
    total.sq_sum += p.sq_sum;
    total.inliers += p.inliers;
  }
  return total;
}

}  // namespace

GicpResult alignGicp(const GicpTarget& target, const Cloud& source,
                     const Pose3& T_target_source_init, const GicpSettings& s) {
  if (s.same_label_only && (source.labels.empty() || target.cloud().labels.empty()))
    throw InputError("alignGicp: same_label_only needs labels on source and target");
  if (!s.point_to_point && source.covariances.size() != source.size())
    throw InputError("alignGicp: GICP needs one covariance per source point");
  if (!source.labels.empty() && source.labels.size() != source.size())
    throw InputError("alignGicp: labels and points differ in size");

  GicpResult result;
  Pose3 T = T_target_source_init;
  for (int it = 0; it < s.max_iterations; ++it) {
    const Linearization lin = linearize(target, source, T, s);
    result.iterations = it + 1;
    if (lin.inliers < s.min_inliers) break;
    Vector6d delta = Vector6d::Zero();
    if (s.min_information > 0) {
      const Eigen::SelfAdjointEigenSolver<Matrix6d> es(lin.H);
      for (int i = 0; i < 6; ++i) {
        const double info = es.eigenvalues()(i);
        if (info < s.min_information) continue;  // unobservable: stays where it started
        const Vector6d v = es.eigenvectors().col(i);
        delta -= v * (v.dot(lin.b) / (info + s.lambda));
      }
    } else {
      Matrix6d H = lin.H;
      H.diagonal().array() += s.lambda;
      delta = H.ldlt().solve(-lin.b);
    }
    if (!delta.allFinite()) break;
    T = T * expSE3(delta);
    if (delta.head<3>().norm() < s.translation_eps && delta.tail<3>().norm() < s.rotation_eps) {
      result.converged = true;
      break;
    }
  }
  // Quality at the final pose.
  const Linearization fin = linearize(target, source, T, s);
  result.T_target_source = T;
  result.num_inliers = fin.inliers;
  result.fitness = source.empty() ? 0.0 : double(fin.inliers) / double(source.size());
  result.rmse = fin.inliers > 0 ? std::sqrt(fin.sq_sum / fin.inliers) : 0.0;
  result.error = fin.cost;
  result.hessian = fin.H;
  if (fin.inliers < s.min_inliers) result.converged = false;
  return result;
}

}  // namespace mapfuse::fusion
