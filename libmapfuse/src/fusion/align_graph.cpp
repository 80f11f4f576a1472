// Multi-trajectory pose graph (eq. (8)-(11)) and GBA (eq. (12)-(14)), Song et al. 2023, in Ceres.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "element_factor.hpp"
#include "factors.hpp"
#include "mapfuse/fusion/align.hpp"
#include "mapfuse/fusion/voxel_hash.hpp"

namespace mapfuse::fusion {

using detail::PoseParams;

namespace {

using PoseSet = std::vector<std::vector<PoseParams>>;

PoseSet makePoses(const std::vector<Lsm>& lsms) {
  PoseSet P(lsms.size());
  for (std::size_t l = 0; l < lsms.size(); ++l) {
    P[l].resize(lsms[l].keyframes.size());
    for (std::size_t k = 0; k < P[l].size(); ++k) P[l][k].set(lsms[l].keyframes[k].T_frame_body);
  }
  return P;
}

// eq. (9) priors and eq. (10) odometry, both from the georeferenced keyframes.
void addPriorsAndOdometry(ceres::Problem& problem, PoseSet& P, const std::vector<Lsm>& priors,
                          const AlignSettings& s, bool yaw_only = false) {
  for (std::size_t l = 0; l < P.size(); ++l) {
    const auto& kfs = priors[l].keyframes;
    for (std::size_t k = 0; k < P[l].size(); ++k) {
      detail::addPose(problem, P[l][k], yaw_only);
      Matrix6d cov = Matrix6d::Zero();
      cov.topLeftCorner<3, 3>() = kfs[k].covariance.topLeftCorner<3, 3>();
      cov.diagonal().tail<3>().setConstant(s.prior_rotation_sigma * s.prior_rotation_sigma);
      cov.topLeftCorner<3, 3>().diagonal().array() += 1e-6;
      problem.AddResidualBlock(
          detail::PosePriorFactor::create(kfs[k].T_frame_body, detail::sqrtInformation<6>(cov)),
          nullptr, P[l][k].t, P[l][k].q);
      if (k == 0) continue;
      const Pose3 rel = kfs[k - 1].T_frame_body.inverse() * kfs[k].T_frame_body;
      const double d = rel.translation().norm();
      const Matrix6d oc =
          diagonalCovariance(std::max(s.odom_min_sigma, s.odom_sigma_per_m * d),
                             std::max(0.1 * s.odom_min_sigma, 0.1 * s.odom_sigma_per_m * d));
      problem.AddResidualBlock(
          detail::RelativePoseFactor::create(rel, detail::sqrtInformation<6>(oc)), nullptr,
          P[l][k - 1].t, P[l][k - 1].q, P[l][k].t, P[l][k].q);
    }
  }
}

// cg_iterations > 0: inexact Gauss-Newton steps by conjugate gradients on the normal equations
// (CGNR, Jacobi preconditioner): GBA's normal equations hold a dense clique of every traversal's
// keyframes at each place, which a sparse Cholesky factorizes at O((traversals * dof)^3) per
// place; CG costs O(nonzeros of J) per iteration.
double solve(ceres::Problem& problem, const AlignSettings& s, double function_tolerance,
             int cg_iterations, bool* converged) {
  ceres::Solver::Options opt;
  opt.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  opt.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  opt.max_num_iterations = s.solver_iterations;
  opt.num_threads = s.threads;
  opt.function_tolerance = function_tolerance;
#if CERES_VERSION_MAJOR == 2 && CERES_VERSION_MINOR < 2
  // CXSparse's simplicial Cholesky beats CHOLMOD's supernodal one (with Debian's ATLAS) on these
  // graphs of small dense cliques (every traversal's keyframes at one place): GBA over 50
  // Karlsruhe traversals 0.54 -> 0.41 s. Ceres 2.2 dropped CXSparse; the default serves there.
  if (ceres::IsSparseLinearAlgebraLibraryTypeAvailable(ceres::CX_SPARSE))
    opt.sparse_linear_algebra_library_type = ceres::CX_SPARSE;
#endif
  if (cg_iterations > 0) {
    opt.linear_solver_type = ceres::CGNR;
    opt.preconditioner_type = ceres::JACOBI;
    opt.max_linear_solver_iterations = cg_iterations;
  }
  ceres::Solver::Summary summary;
  ceres::Solve(opt, &problem, &summary);
  if (converged) *converged = summary.termination_type == ceres::CONVERGENCE;
  return summary.final_cost;
}

void writeBack(std::vector<Lsm>& lsms, const PoseSet& P) {
  for (std::size_t l = 0; l < lsms.size(); ++l)
    for (std::size_t k = 0; k < P[l].size(); ++k) lsms[l].keyframes[k].T_frame_body = P[l][k].get();
}

struct ElementPoint {
  int lsm, kf;
  Eigen::Vector3d body;  // point in anchor body frame
  Eigen::Vector3d dir;   // line direction / plane normal in anchor body frame
  bool plane;
  double weight;  // sqrt of the number of line points it stands for (thinned lines)
};

// Every `line_stride`-th point of a line element (its neighbours add little to a point-to-line
// constraint), weighted so that the line keeps its information; all points of other elements.
std::vector<ElementPoint> elementPoints(const std::vector<Lsm>& lsms, CrowdClass cls,
                                        int line_stride) {
  std::vector<ElementPoint> out;
  for (int l = 0; l < int(lsms.size()); ++l)
    for (const Element& e : lsms[l].elements) {
      if (e.cls != cls || e.points_body.empty()) continue;
      const int k = int(lsms[l].keyframeIndex(e.anchor));
      const auto& pts = e.points_body;
      const GeometryKind kind = geometryKind(cls);
      Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
      if (kind == GeometryKind::kPlanar && pts.size() >= 3) {
        Eigen::Vector3d m = Eigen::Vector3d::Zero();
        for (const auto& p : pts) m += p;
        m /= double(pts.size());
        Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
        for (const auto& p : pts) C += (p - m) * (p - m).transpose();
        normal = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(C).eigenvectors().col(0);
      }
      const std::size_t stride = kind == GeometryKind::kLine ? std::max(1, line_stride) : 1;
      for (std::size_t i = 0; i < pts.size(); i += stride) {
        ElementPoint ep{l,
                        k,
                        pts[i],
                        Eigen::Vector3d::UnitZ(),
                        kind == GeometryKind::kPlanar,
                        std::sqrt(double(std::min(stride, pts.size() - i)))};
        if (kind == GeometryKind::kLine && pts.size() >= 2) {
          const std::size_t a = i == 0 ? 0 : i - 1, b = std::min(pts.size() - 1, i + 1);
          ep.dir = (pts[b] - pts[a]).normalized();
        } else if (kind == GeometryKind::kPlanar) {
          ep.dir = normal;
        }  // pole / light: vertical line through the base point
        out.push_back(ep);
      }
    }
  return out;
}

}  // namespace

double solveMultiPoseGraph(std::vector<Lsm>& lsms, const std::vector<Lsm>& priors,
                           std::vector<InterConstraint>& constraints, const AlignSettings& s,
                           bool* converged) {
  double cost = 0;
  for (int round = 0; round < std::max(1, s.graph_rejection_rounds); ++round) {
    // Later rounds start from the previous solution: only the dropped constraints changed.
    PoseSet P = makePoses(lsms);
    ceres::Problem problem;
    addPriorsAndOdometry(problem, P, priors, s);
    for (const auto& c : constraints) {  // eq. (11), Huber-robust
      if (!c.consistent || c.graph_outlier) continue;
      problem.AddResidualBlock(
          detail::RelativePoseFactor::create(c.T_a_b, detail::sqrtInformation<6>(c.covariance)),
          new ceres::HuberLoss(s.inter_huber), P[c.lsm_a][c.kf_a].t, P[c.lsm_a][c.kf_a].q,
          P[c.lsm_b][c.kf_b].t, P[c.lsm_b][c.kf_b].q);
    }
    cost = solve(problem, s, s.function_tolerance, 0, converged);
    writeBack(lsms, P);
    // Constraints far off the joint solution (lane / dash aliases that PCM could not see because
    // they were consistent within their LSM pair) are dropped and the graph re-solved.
    int dropped = 0;
    for (auto& c : constraints) {
      if (!c.consistent || c.graph_outlier) continue;
      const Pose3 est = lsms[c.lsm_a].keyframes[c.kf_a].T_frame_body.inverse() *
                        lsms[c.lsm_b].keyframes[c.kf_b].T_frame_body;
      const Vector6d e = logSE3(c.T_a_b.inverse() * est);
      c.graph_chi2 = e.dot(c.covariance.ldlt().solve(e));
      if (c.graph_chi2 > s.graph_reject_chi2) {
        c.graph_outlier = true;
        ++dropped;
      }
    }
    if (dropped == 0) break;
  }
  return cost;
}

double solveGba(std::vector<Lsm>& lsms, const std::vector<Lsm>& priors, const AlignSettings& s,
                int* residuals, bool* converged) {
  double cost = 0;
  for (int round = 0; round < std::max(1, s.gba_rounds); ++round) {
    PoseSet P = makePoses(lsms);
    ceres::Problem problem;
    // 4 DOF: roll and pitch are held where georef's gravity prior put them; the normal equations
    // (dense cliques of every traversal's keyframes at one place) shrink from 6 to 4 per pose.
    addPriorsAndOdometry(problem, P, priors, s, s.gba_dof == 4);
    int count = 0;
    for (int c = 0; c < kNumCrowdClasses; ++c) {
      const auto cls = CrowdClass(c);
      const std::vector<ElementPoint> pts = elementPoints(lsms, cls, s.gba_line_stride);
      if (pts.empty()) continue;
      std::vector<Eigen::Vector3d> world(pts.size());
      for (std::size_t i = 0; i < pts.size(); ++i)
        world[i] = lsms[pts[i].lsm].keyframes[pts[i].kf].T_frame_body * pts[i].body;
      // One index over the class; each point keeps its nearest partner in every other traversal.
      const VoxelIndex index(world, std::max(0.1, s.gba_association_distance));
      const double r2 = s.gba_association_distance * s.gba_association_distance;
      struct Partner {
        int lsm, point;
        double d2;
      };
      std::vector<Partner> partners;
      for (int i = 0; i < int(pts.size()); ++i) {
        partners.clear();
        index.forEachWithin(world[i], r2, [&](int j, double d2) {
          const int l = pts[j].lsm;
          if (l == pts[i].lsm) return;
          for (Partner& p : partners)
            if (p.lsm == l) {
              if (d2 < p.d2) p = Partner{l, j, d2};
              return;
            }
          partners.push_back(Partner{l, j, d2});
        });
        std::sort(partners.begin(), partners.end(),
                  [](const Partner& a, const Partner& b) { return a.lsm < b.lsm; });
        // With many traversals, every point is tied to an evenly spread subset of the others
        // (offset rotating with the point), so that each pair of traversals stays coupled while
        // the residual count grows linearly, not quadratically, with the traversals.
        const int n = int(partners.size());
        const int keep = s.gba_max_partners > 0 ? std::min(n, s.gba_max_partners) : n;
        for (int k = 0; k < keep; ++k) {
          const int j = partners[(i + k * n / keep) % n].point;
          const ElementPoint& a = pts[i];
          const ElementPoint& b = pts[j];
          problem.AddResidualBlock(
              new detail::ElementCost(detail::ElementResidual{a.body, b.body, b.dir, b.plane,
                                                              a.weight / s.gba_point_sigma}),
              new ceres::HuberLoss(s.gba_huber), P[a.lsm][a.kf].t, P[a.lsm][a.kf].q,
              P[b.lsm][b.kf].t, P[b.lsm][b.kf].q);
          ++count;
        }
      }
    }
    if (residuals) *residuals = count;
    // Rounds before the last only feed the next association: a looser stop suffices.
    const bool last = round + 1 >= s.gba_rounds;
    cost = solve(problem, s, last ? s.function_tolerance : s.gba_early_round_tolerance,
                 s.gba_cg_iterations, converged);
    writeBack(lsms, P);
  }
  return cost;
}

}  // namespace mapfuse::fusion
