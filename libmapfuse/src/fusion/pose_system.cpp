// Block-sparse normal equations over keyframe poses, solved by PCG with a chain + place-cell
// preconditioner (pose_system.hpp).
#include "pose_system.hpp"

#include <omp.h>
#include <Eigen/Cholesky>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <map>

namespace mapfuse::fusion::detail {

template <int D>
PoseSystem<D>::PoseSystem(const std::vector<int>& chain_sizes) {
  begin_.push_back(0);
  for (std::size_t c = 0; c < chain_sizes.size(); ++c) {
    begin_.push_back(begin_.back() + chain_sizes[c]);
    chain_of_.insert(chain_of_.end(), chain_sizes[c], int(c));
  }
  next_.assign(chain_of_.size(), -1);
}

template <int D>
int PoseSystem<D>::slot(int i, int j) {
  const int a = std::min(i, j), b = std::max(i, j);
  const uint64_t key = (uint64_t(uint32_t(a)) << 32) | uint32_t(b);
  const auto it = slot_of_.find(key);
  if (it != slot_of_.end()) return it->second;
  const int s = int(pair_.size());
  slot_of_.emplace(key, s);
  pair_.emplace_back(a, b);
  if (b == a + 1 && chain_of_[a] == chain_of_[b]) next_[a] = s;
  return s;
}

template <int D>
void PoseSystem<D>::finalize() {
  const int n = poses();
  order_.resize(pair_.size());
  for (int s = 0; s < int(pair_.size()); ++s) order_[s] = s;
  std::sort(order_.begin(), order_.end(), [&](int a, int b) { return pair_[a] < pair_[b]; });
  diag_.assign(n, Block::Zero());
  grad_.assign(n, Vec::Zero());
  off_.assign(pair_.size(), Block::Zero());
}

template <int D>
void PoseSystem<D>::setZero() {
  for (auto& b : diag_) b.setZero();
  for (auto& b : off_) b.setZero();
  for (auto& g : grad_) g.setZero();
}

template <int D>
void PoseSystem<D>::multiply(const std::vector<Block>& diag, const std::vector<Vec>& x,
                             std::vector<Vec>& y, int threads) const {
  // Block by block, each off-diagonal block read once for both of its products (the matrix is
  // larger than the caches: memory traffic bounds this loop). Threads take contiguous ranges of
  // the blocks (sorted by first pose) into their own copy of y, summed at the end.
  const int n = poses();
  const int nb = int(order_.size());
  threads = std::max(1, std::min(threads, nb / 4096 + 1));
  if (int(partial_.size()) < threads - 1) partial_.resize(threads - 1);
#pragma omp parallel num_threads(threads)
  {
    const int t = omp_get_thread_num(), nt = omp_get_num_threads();
    std::vector<Vec>& out = t == 0 ? y : partial_[t - 1];
    out.assign(n, Vec::Zero());
    if (t == 0)
      for (int i = 0; i < n; ++i) out[i].noalias() = diag[i] * x[i];
    const int b0 = int(int64_t(nb) * t / nt), b1 = int(int64_t(nb) * (t + 1) / nt);
    for (int k = b0; k < b1; ++k) {
      const int s = order_[k];
      const int i = pair_[s].first, j = pair_[s].second;
      const Block& B = off_[s];
      out[i].noalias() += B * x[j];
      out[j].noalias() += B.transpose() * x[i];
    }
#pragma omp barrier
    // y += partial sums, rows split among the threads
    const int r0 = int(int64_t(n) * t / nt), r1 = int(int64_t(n) * (t + 1) / nt);
    for (int p = 0; p + 1 < nt; ++p)
      for (int i = r0; i < r1; ++i) y[i] += partial_[p][i];
  }
}

template <int D>
double PoseSystem<D>::modelChange(const std::vector<Vec>& dx) const {
  std::vector<Vec> hx(dx.size());
  multiply(diag_, dx, hx, 1);
  double m = 0;
  for (std::size_t i = 0; i < dx.size(); ++i) m += grad_[i].dot(dx[i]) + 0.5 * dx[i].dot(hx[i]);
  return m;
}

namespace {
/// The coarse level of the preconditioner: A_c = P^T A P, where P maps one D-dof shift per place
/// cell onto every pose of the cell (poses outside every cell, cell -1, are left out).
template <int D>
Eigen::SparseMatrix<double> coarseSystem(const std::vector<Eigen::Matrix<double, D, D>>& A,
                                         const std::vector<Eigen::Matrix<double, D, D>>& off,
                                         const std::vector<std::pair<int, int>>& pairs,
                                         const std::vector<int>& cell, int cells) {
  using Block = Eigen::Matrix<double, D, D>;
  std::map<std::pair<int, int>, Block> acc;  // (ci <= cj)
  auto add = [&](int ci, int cj, const Block& B) {
    if (ci < 0 || cj < 0) return;
    if (ci <= cj)
      acc.try_emplace({ci, cj}, Block::Zero()).first->second += B;
    else
      acc.try_emplace({cj, ci}, Block::Zero()).first->second += B.transpose();
  };
  for (std::size_t i = 0; i < A.size(); ++i) add(cell[i], cell[i], A[i]);
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const int ci = cell[pairs[p].first], cj = cell[pairs[p].second];
    if (ci == cj)
      add(ci, ci, off[p] + off[p].transpose());  // H_ij and H_ji both in the cell's block
    else
      add(ci, cj, off[p]);
  }
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(acc.size() * D * D * 2);
  for (const auto& [key, B] : acc)
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) {
        const double v = key.first == key.second ? 0.5 * (B(a, b) + B(b, a)) : B(a, b);
        t.emplace_back(key.first * D + a, key.second * D + b, v);
        if (key.first != key.second) t.emplace_back(key.second * D + b, key.first * D + a, v);
      }
  Eigen::SparseMatrix<double> Ac(cells * D, cells * D);
  Ac.setFromTriplets(t.begin(), t.end());
  return Ac;
}
}  // namespace

template <int D>
PcgStats PoseSystem<D>::solve(double mu, const std::vector<int>& cell, const PcgSettings& s,
                              std::vector<Vec>& dx) const {
  const int n = poses();
  // Levenberg-Marquardt damping: mu times the (clamped) diagonal of H, as Ceres scales it.
  std::vector<Block> A(diag_);
  for (auto& b : A)
    for (int k = 0; k < D; ++k) b(k, k) += mu * std::clamp(b(k, k), 1e-6, 1e32);

  // Fine level: block LDL^T of each chain's tridiagonal part. S_k = A_kk - C^T S_{k-1}^-1 C with
  // C = A_{k-1,k}; W_k = S_k^-1 A_{k,k+1}.
  std::vector<Eigen::LLT<Block>> S(n);
  std::vector<Block> W(n, Block::Zero());
#pragma omp parallel for schedule(dynamic) num_threads(s.threads)
  for (int c = 0; c < chains(); ++c)
    for (int k = begin_[c]; k < begin_[c + 1]; ++k) {
      Block Sk = A[k];
      if (k > begin_[c] && next_[k - 1] >= 0)
        Sk.noalias() -= off_[next_[k - 1]].transpose() * W[k - 1];
      S[k].compute(Sk);
      if (k + 1 < begin_[c + 1] && next_[k] >= 0) W[k] = S[k].solve(off_[next_[k]]);
    }
  auto chainSolve = [&](const std::vector<Vec>& r, std::vector<Vec>& z) {
#pragma omp parallel for schedule(dynamic) num_threads(s.threads)
    for (int c = 0; c < chains(); ++c) {
      const int b = begin_[c], e = begin_[c + 1];
      Vec y = Vec::Zero();
      for (int k = b; k < e; ++k) {
        Vec yk = r[k];
        if (k > b && next_[k - 1] >= 0) yk.noalias() -= off_[next_[k - 1]].transpose() * y;
        y = S[k].solve(yk);  // z_k before the back substitution
        z[k] = y;
      }
      for (int k = e - 2; k >= b; --k)
        if (next_[k] >= 0) z[k].noalias() -= W[k] * z[k + 1];
    }
  };

  // Coarse level: one D-dof shift per cell, A_c = P^T A P.
  const int cells = cell.empty() ? 0 : *std::max_element(cell.begin(), cell.end()) + 1;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> coarse;
  if (cells > 0) coarse.compute(coarseSystem<D>(A, off_, pair_, cell, cells));
  const bool use_coarse = cells > 0 && coarse.info() == Eigen::Success;
  auto precondition = [&](const std::vector<Vec>& r, std::vector<Vec>& z) {
    chainSolve(r, z);
    if (!use_coarse) return;
    Eigen::VectorXd rc = Eigen::VectorXd::Zero(cells * D);
    for (int i = 0; i < n; ++i)
      if (cell[i] >= 0) rc.segment<D>(cell[i] * D) += r[i];
    const Eigen::VectorXd zc = coarse.solve(rc);
    for (int i = 0; i < n; ++i)
      if (cell[i] >= 0) z[i] += zc.segment<D>(cell[i] * D);
  };

  // PCG on A dx = -g.
  PcgStats stats;
  dx.assign(n, Vec::Zero());
  std::vector<Vec> r(n), z(n), p(n), q(n);
  double bnorm = 0;
  for (int i = 0; i < n; ++i) {
    r[i] = -grad_[i];
    bnorm += r[i].squaredNorm();
  }
  bnorm = std::sqrt(bnorm);
  if (bnorm == 0) return stats;
  precondition(r, z);
  p = z;
  double rz = 0;
  for (int i = 0; i < n; ++i) rz += r[i].dot(z[i]);
  for (int it = 0; it < s.max_iterations; ++it) {
    multiply(A, p, q, s.threads);
    double pq = 0;
    for (int i = 0; i < n; ++i) pq += p[i].dot(q[i]);
    if (!(pq > 0)) break;
    const double alpha = rz / pq;
    double rr = 0;
    for (int i = 0; i < n; ++i) {
      dx[i] += alpha * p[i];
      r[i] -= alpha * q[i];
      rr += r[i].squaredNorm();
    }
    stats.iterations = it + 1;
    stats.relative_residual = std::sqrt(rr) / bnorm;
    if (stats.relative_residual <= s.tolerance) break;
    precondition(r, z);
    double rz_new = 0;
    for (int i = 0; i < n; ++i) rz_new += r[i].dot(z[i]);
    const double beta = rz_new / rz;
    rz = rz_new;
    for (int i = 0; i < n; ++i) p[i] = z[i] + beta * p[i];
  }
  return stats;
}

template class PoseSystem<4>;
template class PoseSystem<6>;

}  // namespace mapfuse::fusion::detail
