#pragma once
/// @file Gauss-Newton normal equations over the keyframe poses of many traversals, and their
/// solution in time linear in the number of poses (private to libmapfuse/src/fusion).
///
/// Poses are numbered chain after chain (one chain per LSM, consecutive keyframes adjacent).
/// H is block-sparse with D x D blocks (D = 6: full pose; D = 4: x, y, z, yaw): one diagonal
/// block per pose and one block per pair of poses some factor couples (odometry: consecutive
/// keyframes; InterRPCs and GBA element residuals: keyframes of two traversals at one place).
///
/// A direct sparse Cholesky of H costs O((traversals x D)^3) per place: every elimination order
/// of many parallel chains tied together at each place leaves a separator of all traversals
/// there (docs/fusion.md). `solve` runs preconditioned conjugate gradients instead, each
/// iteration O(blocks), with a two-level preconditioner:
/// - fine level: each chain's block-tridiagonal part (its diagonal and odometry blocks), solved
///   exactly by block Cholesky along the chain, O(keyframes x D^3): handles the stiff odometry
///   of one traversal;
/// - coarse level: one D-dof shift per place cell (every pose in the cell moves together),
///   A_c = P^T A P factorised once per solve (a few thousand unknowns per 20 km of road): the
///   modes where all traversals at a place move together are constrained only by the weak GPS
///   priors, and conjugate gradients with the fine level alone needed hundreds of iterations
///   for them.
/// Both levels act additively (z = M_f^-1 r + P A_c^-1 P^T r), a symmetric positive definite
/// preconditioner, so the iteration count depends on neither the traversals nor the road.
#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace mapfuse::fusion::detail {

/// Conjugate-gradient settings of one linear solve.
struct PcgSettings {
  int max_iterations = 100;  ///< per solve
  double tolerance = 1e-6;   ///< stop at |r| <= tolerance |b| (preconditioned residual norm)
  int threads = 2;           ///< OpenMP threads of the matrix-vector product and the chains
};

/// What one linear solve did.
struct PcgStats {
  int iterations = 0;
  double relative_residual = 0;  ///< |r| / |b| at the end
};

template <int D>
class PoseSystem {
 public:
  using Block = Eigen::Matrix<double, D, D>;
  using Vec = Eigen::Matrix<double, D, 1>;

  /// @param chain_sizes poses per chain; poses are numbered chain after chain
  explicit PoseSystem(const std::vector<int>& chain_sizes);

  int poses() const { return int(chain_of_.size()); }
  int chainBegin(int c) const { return begin_[c]; }
  int chains() const { return int(begin_.size()) - 1; }

  /// @brief Structure: the slot of the block that couples poses i != j, created on first call.
  /// Call before `finalize`; consecutive poses of a chain get the chain's odometry slot.
  int slot(int i, int j);
  /// @brief Freezes the structure (row lists); values can then be accumulated and solved.
  void finalize();
  /// @brief Zeroes every block and the gradient, keeping the structure.
  void setZero();
  int blocks() const { return int(pair_.size()); }

  /// @brief Adds w J^T J to pose i's diagonal block and w J^T r to its gradient.
  template <int R>
  void addUnary(int i, const Eigen::Matrix<double, R, D>& J, const Eigen::Matrix<double, R, 1>& r,
                double w) {
    diag_[i].noalias() += w * J.transpose() * J;
    grad_[i].noalias() += w * J.transpose() * r;
  }
  /// @brief Adds a term coupling poses i and j (through `slot` of the pair).
  template <int R>
  void addBinary(int slot, int i, int j, const Eigen::Matrix<double, R, D>& Ji,
                 const Eigen::Matrix<double, R, D>& Jj, const Eigen::Matrix<double, R, 1>& r,
                 double w) {
    addBinaryOwned<R>(slot, i, j, Ji, Jj, r, w, [](int) { return true; });
  }
  /// @brief addBinary restricted to the blocks a thread owns: pose p's diagonal block and
  /// gradient when mine(p), the coupling block when mine(min(i, j)). Threads owning disjoint
  /// poses that each run one list of terms through it add every block's terms in list order:
  /// the sums of a serial addBinary loop, bit for bit.
  template <int R, class Mine>
  void addBinaryOwned(int slot, int i, int j, const Eigen::Matrix<double, R, D>& Ji,
                      const Eigen::Matrix<double, R, D>& Jj, const Eigen::Matrix<double, R, 1>& r,
                      double w, const Mine& mine) {
    const bool own_i = mine(i), own_j = mine(j), own_off = mine(std::min(i, j));
    if (!own_i && !own_j && !own_off) return;
    const Eigen::Matrix<double, D, R> wJi = w * Ji.transpose(), wJj = w * Jj.transpose();
    if (own_i) diag_[i].noalias() += wJi * Ji;
    if (own_j) diag_[j].noalias() += wJj * Jj;
    if (own_i) grad_[i].noalias() += wJi * r;
    if (own_j) grad_[j].noalias() += wJj * r;
    if (!own_off) return;
    if (i < j)
      off_[slot].noalias() += wJi * Jj;
    else
      off_[slot].noalias() += wJj * Ji;
  }

  /// @brief Solves (H + mu diag(H)) dx = -g by PCG. `cell` gives each pose's coarse cell
  /// (0..cells-1); empty: fine level only. dx is sized and zero-started here.
  PcgStats solve(double mu, const std::vector<int>& cell, const PcgSettings& s,
                 std::vector<Vec>& dx) const;

  /// @brief g^T dx + dx^T H dx / 2, the Gauss-Newton model change of a step.
  double modelChange(const std::vector<Vec>& dx) const;

 private:
  void multiply(const std::vector<Block>& diag, const std::vector<Vec>& x, std::vector<Vec>& y,
                int threads) const;
  std::vector<int> begin_;     // chain c: poses [begin_[c], begin_[c + 1])
  std::vector<int> chain_of_;  // pose -> chain
  std::unordered_map<uint64_t, int> slot_of_;
  std::vector<std::pair<int, int>> pair_;  // slot -> (i < j)
  std::vector<int> next_;                  // pose i -> slot of (i, i + 1) in its chain, or -1
  std::vector<int> order_;                 // slots sorted by their first pose
  mutable std::vector<std::vector<Vec>> partial_;  // per-thread products of `multiply`
  std::vector<Block> diag_, off_;
  std::vector<Vec> grad_;

 public:
  Block& diag(int i) { return diag_[i]; }
  Vec& grad(int i) { return grad_[i]; }
  const std::vector<Vec>& gradient() const { return grad_; }
};

extern template class PoseSystem<4>;
extern template class PoseSystem<6>;

}  // namespace mapfuse::fusion::detail
