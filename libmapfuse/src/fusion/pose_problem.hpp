#pragma once
/// @file Nonlinear least squares over the keyframe poses of many traversals: pose priors
/// (eq. (9)), relative poses (odometry eq. (10), InterRPCs eq. (11)) and GBA element residuals
/// (eq. (12)-(14)), Song et al. 2023, minimised by Levenberg-Marquardt with Ceres' trust-region
/// rule; each step is a PCG solve of the block-sparse normal equations (pose_system.hpp), so
/// that one iteration costs O(poses + residuals) whatever the number of traversals at a place.
/// Robust terms (Huber, as ceres::HuberLoss) enter the normal equations with their IRLS weight
/// rho'; the minimum is the same as with Ceres' corrected residuals (the gradients agree).
/// Private to libmapfuse/src/fusion.
#include <Eigen/Core>
#include <vector>

#include "pose_factors.hpp"
#include "pose_system.hpp"

namespace mapfuse::fusion::detail {

struct PoseProblemSettings {
  int max_iterations = 100;          ///< LM iterations
  double function_tolerance = 1e-3;  ///< stop when |cost change| / cost falls below
  double cell_size = 40.0;           ///< m, place cells of the coarse preconditioner (0: none)
  double initial_radius = 1e4;       ///< LM trust region at the start (damping 1 / radius)
  PcgSettings pcg;
};

struct PoseProblemResult {
  double initial_cost = 0, final_cost = 0;  ///< Ceres convention: sum of rho(|r|^2) / 2
  int iterations = 0;                       ///< LM iterations (accepted or not)
  int pcg_iterations = 0;                   ///< summed over the linear solves
  bool converged = false;                   ///< the function tolerance was met
  int blocks = 0;                           ///< off-diagonal blocks of the normal equations
};

/// Poses with D = 6 (full) or 4 (x, y, z, yaw: roll and pitch stay as they are) free dof.
template <int D>
class PoseProblem {
 public:
  /// @param chain_sizes keyframes per traversal; @param poses initial poses, chain after chain
  PoseProblem(const std::vector<int>& chain_sizes, std::vector<PoseVar> poses);

  int poseIndex(int chain, int k) const { return begin_[chain] + k; }
  const std::vector<PoseVar>& poses() const { return x_; }

  /// @brief Eq. (9): pose i stays near x0 with square-root information L (6 x 6).
  void addPrior(int i, const PoseVar& x0, const Matrix6d& L);
  /// @brief Eq. (10) / (11): T_i^-1 T_j = T_ij; `huber` > 0 makes it robust. @return its index.
  int addRelative(int i, int j, const Pose3& T_ij, const Matrix6d& L, double huber = 0);
  /// @brief Whitened squared residual of relative term `r` at the current poses.
  double relativeChi2(int r) const;

  /// @brief A GBA element point (body frame of pose `pose`; line direction or plane normal).
  int addElementPoint(int pose, const Eigen::Vector3d& body, const Eigen::Vector3d& dir, bool plane,
                      double inv_sigma);
  /// @brief Eq. (12)-(14): point a lies on the line / plane of point b (Huber `element_huber`).
  void addElementPair(int a, int b);
  /// @brief Room for `n` element points in all (the GBA knows their number before adding them).
  void reserveElementPoints(std::size_t n) { points_.reserve(n); }
  void setElementHuber(double delta) { element_huber_ = delta; }
  std::size_t elementPairs() const { return pairs_.size(); }
  /// @brief Drops every element pair (the next association round adds its own).
  void clearElementPairs();

  /// @brief Current total cost (sum of rho(|r|^2) / 2).
  double cost() const { return evaluate(x_); }
  PoseProblemResult solve(const PoseProblemSettings& s);

 private:
  using Sys = PoseSystem<D>;
  template <int R>
  static Eigen::Matrix<double, R, D> cols(const Eigen::Matrix<double, R, 6>& J);
  double evaluate(const std::vector<PoseVar>& x) const;
  double linearize(Sys& sys, const std::vector<int>& rel_slot, const std::vector<int>& pair_slot,
                   int threads) const;

  std::vector<int> chain_sizes_, begin_;
  std::vector<PoseVar> x_;
  struct Prior {
    int i;
    PoseVar x0;
    Matrix6d L;
  };
  struct Relative {
    int i, j;
    Eigen::Vector3d t;
    Eigen::Quaterniond q;
    Matrix6d L;
    double huber;
  };
  struct Point {
    int pose;
    Eigen::Vector3f body, dir;  // float: within tens of metres of the pose, 4 um steps
    float inv_sigma;
    bool plane;
  };
  struct Pair {
    int a, b;
  };
  std::vector<Prior> priors_;
  std::vector<Relative> relatives_;
  std::vector<Point> points_;
  std::vector<Pair> pairs_;
  double element_huber_ = 1.0;
};

extern template class PoseProblem<4>;
extern template class PoseProblem<6>;

}  // namespace mapfuse::fusion::detail
