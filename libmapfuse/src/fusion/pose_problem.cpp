// Levenberg-Marquardt over keyframe poses with PCG steps (pose_problem.hpp).
#include "pose_problem.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace mapfuse::fusion::detail {
namespace {

Vector6d priorResidual(const PoseVar& x, const PoseVar& x0, const Matrix6d& L) {
  Vector6d u;
  u.head<3>() = x.t - x0.t;
  u.tail<3>() = 2.0 * (x0.q.conjugate() * x.q).vec();
  return L * u;
}

Vector6d relativeResidual(const PoseVar& a, const PoseVar& b, const Eigen::Vector3d& t,
                          const Eigen::Quaterniond& q, const Matrix6d& L) {
  Vector6d u;
  u.head<3>() = a.q.conjugate() * (b.t - a.t) - t;
  u.tail<3>() = 2.0 * (q.conjugate() * (a.q.conjugate() * b.q)).vec();
  return L * u;
}

}  // namespace

template <int D>
PoseProblem<D>::PoseProblem(const std::vector<int>& chain_sizes, std::vector<PoseVar> poses)
    : chain_sizes_(chain_sizes), x_(std::move(poses)) {
  begin_.push_back(0);
  for (int n : chain_sizes_) begin_.push_back(begin_.back() + n);
}

template <int D>
void PoseProblem<D>::addPrior(int i, const PoseVar& x0, const Matrix6d& L) {
  priors_.push_back({i, x0, L});
}

template <int D>
int PoseProblem<D>::addRelative(int i, int j, const Pose3& T_ij, const Matrix6d& L, double huber) {
  relatives_.push_back(
      {i, j, T_ij.translation(), Eigen::Quaterniond(T_ij.linear()).normalized(), L, huber});
  return int(relatives_.size()) - 1;
}

template <int D>
double PoseProblem<D>::relativeChi2(int r) const {
  const Relative& f = relatives_[r];
  return relativeResidual(x_[f.i], x_[f.j], f.t, f.q, f.L).squaredNorm();
}

template <int D>
int PoseProblem<D>::addElementPoint(int pose, const Eigen::Vector3d& body,
                                    const Eigen::Vector3d& dir, bool plane, double inv_sigma) {
  points_.push_back({pose, body.cast<float>(), dir.cast<float>(), float(inv_sigma), plane});
  return int(points_.size()) - 1;
}

template <int D>
void PoseProblem<D>::addElementPair(int a, int b) {
  pairs_.push_back({a, b});
}

template <int D>
void PoseProblem<D>::clearElementPairs() {
  pairs_.clear();
  pairs_.shrink_to_fit();
}

template <int D>
template <int R>
Eigen::Matrix<double, R, D> PoseProblem<D>::cols(const Eigen::Matrix<double, R, 6>& J) {
  if constexpr (D == 6) {
    return J;
  } else {
    Eigen::Matrix<double, R, D> out;
    out << J.template leftCols<3>(), J.col(5);
    return out;
  }
}

template <int D>
double PoseProblem<D>::evaluate(const std::vector<PoseVar>& x) const {
  double cost = 0;
  for (const Prior& p : priors_) cost += 0.5 * priorResidual(x[p.i], p.x0, p.L).squaredNorm();
  for (const Relative& f : relatives_) {
    const double s = relativeResidual(x[f.i], x[f.j], f.t, f.q, f.L).squaredNorm();
    cost += f.huber > 0 ? huberCost(s, f.huber) : 0.5 * s;
  }
  const int n = int(pairs_.size());
  double element = 0;
#pragma omp parallel for reduction(+ : element) schedule(static, 4096)
  for (int k = 0; k < n; ++k) {
    const Point& a = points_[pairs_[k].a];
    const Point& b = points_[pairs_[k].b];
    const PoseVar &pa = x[a.pose], &pb = x[b.pose];
    const Eigen::Vector3d d = pa.q * a.body.template cast<double>() + pa.t -
                              (pb.q * b.body.template cast<double>() + pb.t);
    const Eigen::Vector3d u = pb.q * b.dir.template cast<double>();
    const double ud = u.dot(d);
    const double s = a.inv_sigma * a.inv_sigma * (b.plane ? ud * ud : (d - u * ud).squaredNorm());
    element += huberCost(s, element_huber_);
  }
  return cost + element;
}

template <int D>
double PoseProblem<D>::linearize(Sys& sys, const std::vector<int>& rel_slot,
                                 const std::vector<int>& pair_slot, int threads) const {
  double cost = 0;
  for (const Prior& p : priors_) {
    const PriorTerm t = priorTerm(x_[p.i], p.x0, p.L);
    sys.template addUnary<6>(p.i, cols<6>(t.J), t.r, 1.0);
    cost += 0.5 * t.r.squaredNorm();
  }
  for (std::size_t k = 0; k < relatives_.size(); ++k) {
    const Relative& f = relatives_[k];
    const RelativeTerm t = relativeTerm(x_[f.i], x_[f.j], f.t, f.q, f.L);
    const double s = t.r.squaredNorm();
    const double w = f.huber > 0 ? huberWeight(s, f.huber) : 1.0;
    cost += f.huber > 0 ? huberCost(s, f.huber) : 0.5 * s;
    sys.template addBinary<6>(rel_slot[k], f.i, f.j, cols<6>(t.Ja), cols<6>(t.Jb), t.r, w);
  }
  // Element pairs (most of the work): a chunk's terms on all threads, then each thread adds the
  // terms into the blocks of its range of poses, the chunk in pair order, and thread 0 sums the
  // costs in pair order: the serial loop's sums bit for bit, whatever the thread count.
  struct PairTerm {
    Eigen::Matrix<double, 3, D> Ja, Jb;
    Eigen::Vector3d r;
    double w, cost;
  };
  constexpr int kChunk = 32768;  // 7.6 MB of terms (D = 4): few barriers
  const int n = int(pairs_.size()), poses = int(x_.size());
  std::vector<PairTerm> terms(std::min(n, kChunk));
#pragma omp parallel num_threads(std::max(1, threads))
  {
    const int t = omp_get_thread_num(), nt = omp_get_num_threads();
    const int p0 = int(int64_t(poses) * t / nt), p1 = int(int64_t(poses) * (t + 1) / nt);
    const auto mine = [p0, p1](int p) { return p >= p0 && p < p1; };
    for (int c0 = 0; c0 < n; c0 += kChunk) {
      const int c1 = std::min(n, c0 + kChunk);
#pragma omp for schedule(static)
      for (int k = c0; k < c1; ++k) {
        const Point& a = points_[pairs_[k].a];
        const Point& b = points_[pairs_[k].b];
        const ElementTerm e = elementTerm(x_[a.pose], x_[b.pose], a.body.template cast<double>(),
                                          b.body.template cast<double>(),
                                          b.dir.template cast<double>(), b.plane, a.inv_sigma);
        PairTerm& pt = terms[k - c0];
        const double s = e.r.squaredNorm();
        pt.w = huberWeight(s, element_huber_);
        pt.cost = huberCost(s, element_huber_);
        pt.Ja = cols<3>(e.Ja);
        pt.Jb = cols<3>(e.Jb);
        pt.r = e.r;
      }  // implied barrier: the chunk's terms are complete
      for (int k = c0; k < c1; ++k) {
        const PairTerm& pt = terms[k - c0];
        const int ia = points_[pairs_[k].a].pose, ib = points_[pairs_[k].b].pose;
        if (t == 0) cost += pt.cost;
        if (points_[pairs_[k].b].plane) {  // one row
          const Eigen::Matrix<double, 1, D> Ja = pt.Ja.template topRows<1>(),
                                            Jb = pt.Jb.template topRows<1>();
          sys.template addBinaryOwned<1>(pair_slot[k], ia, ib, Ja, Jb, pt.r.template head<1>(),
                                         pt.w, mine);
        } else {
          sys.template addBinaryOwned<3>(pair_slot[k], ia, ib, pt.Ja, pt.Jb, pt.r, pt.w, mine);
        }
      }
#pragma omp barrier
    }
  }
  return cost;
}

template <int D>
PoseProblemResult PoseProblem<D>::solve(const PoseProblemSettings& s) {
  Sys sys(chain_sizes_);
  std::vector<int> rel_slot(relatives_.size()), pair_slot(pairs_.size());
  for (std::size_t k = 0; k < relatives_.size(); ++k)
    rel_slot[k] = sys.slot(relatives_[k].i, relatives_[k].j);
  for (std::size_t k = 0; k < pairs_.size(); ++k)
    pair_slot[k] = sys.slot(points_[pairs_[k].a].pose, points_[pairs_[k].b].pose);
  sys.finalize();
  // Place cells of the coarse preconditioner, from the starting positions.
  std::vector<int> cell;
  if (s.cell_size > 0) {
    std::map<std::pair<int64_t, int64_t>, int> ids;
    cell.resize(x_.size());
    for (std::size_t i = 0; i < x_.size(); ++i) {
      const std::pair<int64_t, int64_t> key{int64_t(std::floor(x_[i].t.x() / s.cell_size)),
                                            int64_t(std::floor(x_[i].t.y() / s.cell_size))};
      cell[i] = ids.try_emplace(key, int(ids.size())).first->second;
    }
  }
  PoseProblemResult res;
  res.blocks = sys.blocks();
  double radius = s.initial_radius, decrease = 2.0;  // Ceres' LM rule
  double cost = res.initial_cost = res.final_cost = evaluate(x_);
  std::vector<typename Sys::Vec> dx;
  for (int it = 0; it < s.max_iterations; ++it) {
    sys.setZero();
    cost = linearize(sys, rel_slot, pair_slot, s.pcg.threads);
    bool accepted = false;
    while (!accepted && radius > 1e-32) {
      ++res.iterations;
      const PcgStats ps = sys.solve(1.0 / radius, cell, s.pcg, dx);
      res.pcg_iterations += ps.iterations;
      const double model = -sys.modelChange(dx);
      std::vector<PoseVar> x = x_;
      for (std::size_t i = 0; i < x.size(); ++i) {
        Vector6d d = Vector6d::Zero();
        if constexpr (D == 6) {
          d = dx[i];
        } else {
          d << dx[i](0), dx[i](1), dx[i](2), 0, 0, dx[i](3);
        }
        x[i].plus(d);
      }
      const double new_cost = evaluate(x);
      const double rho = model > 0 ? (cost - new_cost) / model : -1.0;
      if (rho > 1e-3) {
        accepted = true;
        x_ = std::move(x);
        radius /= std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * rho - 1.0, 3));
        decrease = 2.0;
        const double change = cost - new_cost;
        cost = new_cost;
        if (change <= s.function_tolerance * cost) res.converged = true;
      } else {
        radius /= decrease;
        decrease *= 2.0;
        if (model <= 0 && ps.relative_residual <= s.pcg.tolerance) {  // at the minimum
          res.converged = true;
          break;
        }
      }
      if (res.iterations >= s.max_iterations) break;
    }
    if (res.converged || !accepted || res.iterations >= s.max_iterations) break;
  }
  res.final_cost = cost;
  return res;
}

template class PoseProblem<4>;
template class PoseProblem<6>;

}  // namespace mapfuse::fusion::detail
