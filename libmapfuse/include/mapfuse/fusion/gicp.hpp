#pragma once
/// @file Generalized ICP (Segal et al. 2009) with semantic correspondences: the registration core
/// of SGICP (eq. (7), Song et al. 2023) and of LiDAR scan-to-map odometry.
///
/// Cost: sum_i w_l(i) rho( r_i^T (C_i^t + R C_i^s R^T)^-1 r_i ), r_i = t_i - T s_i, where t_i is
/// the nearest target point (same label when `same_label_only`), w_l a per-label weight and rho
/// an optional Huber loss. Gauss-Newton on SE(3) with analytic Jacobians (right perturbation
/// T <- T exp(xi), xi = (rho, phi)); nearest neighbours from a voxel hash (27-cell lookup).
#include <cstdint>
#include <memory>
#include <vector>

#include "mapfuse/core/se3.hpp"
#include "mapfuse/fusion/point_cloud.hpp"
#include "mapfuse/fusion/voxel_hash.hpp"

namespace mapfuse::fusion {

struct GicpSettings {
  double max_correspondence_distance = 1.0;  ///< m; exact NN when <= the target index voxel size
  int max_iterations = 30;                   ///< Gauss-Newton iterations
  double translation_eps = 1e-4;             ///< m; converged when the step is below both eps
  double rotation_eps = 1e-4;                ///< rad
  bool same_label_only = false;              ///< correspondences only within a label (needs labels)
  std::vector<double> label_weights;  ///< w_l per label value (empty = all 1); 0 drops a label
  double huber_delta = 0.0;  ///< Huber threshold on the Mahalanobis distance (0 = squared loss)
  std::vector<double> label_huber_delta;  ///< per-label Huber threshold (overrides huber_delta)
  bool point_to_point = false;            ///< ignore covariances (plain point-to-point ICP)
  double lambda = 1e-6;                   ///< Levenberg damping added to the Hessian diagonal
  /// > 0: directions of the Hessian (information, when residuals are whitened by covariances)
  /// with an eigenvalue below this are unobservable and the steps leave them alone (solution
  /// remapping, Zhang et al. 2016): along a lone straight line the translation along it is free,
  /// and undamped steps there oscillated until max_iterations instead of converging.
  double min_information = 0.0;
  int min_inliers = 6;  ///< fewer correspondences than this: stop, not converged
  int num_threads = 1;  ///< OpenMP threads for the per-point loop
};

struct GicpResult {
  Pose3 T_target_source = Pose3::Identity();
  bool converged = false;
  int iterations = 0;
  int num_inliers = 0;   ///< correspondences at the final pose
  double fitness = 0.0;  ///< num_inliers / source size
  double rmse = 0.0;     ///< m, Euclidean RMS of inlier residuals at the final pose
  double error = 0.0;    ///< final weighted GICP cost (sum of robustified Mahalanobis^2)
  Matrix6d hessian = Matrix6d::Zero();  ///< J^T W J at the final pose, (rho, phi) order
};

/// A registration target: a cloud (with covariances unless only point-to-point is used) and its
/// voxel-hash index, one per label when labels are present.
class GicpTarget {
 public:
  /// @param cloud target cloud; covariances are estimated when missing
  /// @param index_voxel_size NN index cell, m; use >= max_correspondence_distance for exact NN
  explicit GicpTarget(Cloud cloud, double index_voxel_size = 1.0);
  const Cloud& cloud() const { return cloud_; }
  /// @brief Nearest target point (any label, or `label` when >= 0) within sqrt(max_dist_sq).
  int nearest(const Eigen::Vector3d& q, int label, double max_dist_sq, double* dist_sq) const;

 private:
  Cloud cloud_;
  VoxelIndex all_;
  std::vector<std::unique_ptr<VoxelIndex>> per_label_;  ///< index of label -> points of label
  std::vector<std::vector<int>> label_members_;         ///< per label: indices into cloud_
};

/// @brief Registers `source` to `target` starting at T_target_source_init.
/// @throws InputError when labels are required but missing, or covariances are missing on a
/// GICP (not point-to-point) source.
GicpResult alignGicp(const GicpTarget& target, const Cloud& source,
                     const Pose3& T_target_source_init, const GicpSettings& settings);

}  // namespace mapfuse::fusion
