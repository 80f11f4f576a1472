// Multi-trajectory pose graph (eq. (8)-(11)) and GBA (eq. (12)-(14)), Song et al. 2023, solved
// by Levenberg-Marquardt with PCG steps over the keyframe poses (pose_problem.hpp): every
// iteration costs O(keyframes + residuals), whatever the number of traversals at a place.
#include <omp.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <unordered_map>

#include "gps_bias.hpp"
#include "graph_covariances.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/core/parallel_for.hpp"
#include "mapfuse/fusion/align.hpp"
#include "mapfuse/fusion/voxel_hash.hpp"
#include "pose_problem.hpp"

namespace mapfuse::fusion {

namespace {

using detail::PoseProblem;
using detail::PoseVar;
using detail::sqrtInformation;

std::vector<int> chainSizes(const std::vector<Lsm>& lsms) {
  std::vector<int> n;
  for (const auto& l : lsms) n.push_back(int(l.keyframes.size()));
  return n;
}

int keyframeCount(const std::vector<Lsm>& lsms) {
  int n = 0;
  for (const auto& l : lsms) n += int(l.keyframes.size());
  return n;
}

std::vector<PoseVar> posesOf(const std::vector<Lsm>& lsms) {
  std::vector<PoseVar> x;
  for (const auto& l : lsms)
    for (const auto& k : l.keyframes) x.push_back(PoseVar::from(k.T_frame_body));
  return x;
}

template <int D>
void writeBack(std::vector<Lsm>& lsms, const PoseProblem<D>& P) {
  for (int l = 0; l < int(lsms.size()); ++l)
    for (int k = 0; k < int(lsms[l].keyframes.size()); ++k)
      lsms[l].keyframes[k].T_frame_body = P.poses()[P.poseIndex(l, k)].pose();
}

// The problem over the keyframes of `lsms` (as they are now) and the GPS bias nodes of `g`.
template <int D>
PoseProblem<D> makeProblem(const std::vector<Lsm>& lsms, const std::vector<Lsm>& priors,
                           const detail::GpsPriorTerms& g) {
  std::vector<int> sizes = chainSizes(lsms);
  std::vector<PoseVar> x = posesOf(lsms);
  for (const auto& nodes : g.nodes) sizes.push_back(int(nodes.size()));
  for (const Pose3& T : detail::gpsBiasNodeStart(g, lsms, priors)) x.push_back(PoseVar::from(T));
  return PoseProblem<D>(sizes, std::move(x));
}

// eq. (9) priors (with the GPS bias nodes, gps_bias.hpp) and eq. (10) odometry, both from the
// georeferenced keyframes.
template <int D>
void addPriorsAndOdometry(PoseProblem<D>& P, const std::vector<Lsm>& priors,
                          const detail::GpsPriorTerms& g, const AlignSettings& s) {
  for (const auto& a : g.anchors)
    P.addPrior(P.poseIndex(a.chain, a.index), PoseVar::from(a.T0), a.L);
  for (const auto& t : g.terms)
    P.addRelative(P.poseIndex(t.chain_a, t.index_a), P.poseIndex(t.chain_b, t.index_b), t.T_ab,
                  t.L);
  for (int l = 0; l < int(priors.size()); ++l) {
    const auto& kfs = priors[l].keyframes;
    for (int k = 1; k < int(kfs.size()); ++k) {
      const Pose3 rel = kfs[k - 1].T_frame_body.inverse() * kfs[k].T_frame_body;
      P.addRelative(P.poseIndex(l, k - 1), P.poseIndex(l, k), rel,
                    sqrtInformation(detail::odometryCovariance(rel, s)));
    }
  }
}

// One solve's figures into the run's: the last cost and convergence, iterations summed.
template <class SolveSummary>
void addSolve(GraphSolve& out, const SolveSummary& r, int keyframes) {
  out.cost = r.final_cost;
  out.converged = r.converged;
  out.iterations += r.iterations;
  out.pcg_iterations += r.pcg_iterations;
  out.blocks = r.blocks;
  out.keyframes = keyframes;
  ++out.rounds;
}

detail::PoseProblemSettings problemSettings(const AlignSettings& s, double function_tolerance) {
  detail::PoseProblemSettings p;
  p.max_iterations = s.solver_iterations;
  p.function_tolerance = function_tolerance;
  p.pcg.max_iterations = s.pcg_iterations;
  p.pcg.tolerance = s.pcg_tolerance;
  p.pcg.threads = s.threads;
  p.cell_size = s.pcg_cell_size;
  return p;
}

struct ElementPoint {
  int lsm, kf;
  Eigen::Vector3d body;  // point in anchor body frame
  Eigen::Vector3d dir;   // line direction / plane normal in anchor body frame
  bool plane;
  double weight;  // sqrt of the number of line points it stands for (thinned lines)
};

// What the association reads of an element point: its pose and its point in the body frame.
struct AnchoredPoint {
  int lsm, kf;
  Eigen::Vector3d body;
};

// Every `line_stride`-th point of a line element (its neighbours add little to a point-to-line
// constraint), weighted so that the line keeps its information; all points of other elements.
// Calls visit(ElementPoint) for each, in a fixed order.
template <class Visit>
void forEachElementPoint(const std::vector<Lsm>& lsms, CrowdClass cls, int line_stride,
                         Visit&& visit) {
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
        visit(ep);
      }
    }
}

// GBA association of one class (eq. (12)): each point is tied to the nearest point of at most
// `gba_max_partners` other traversals within the association distance. The partner traversals
// are chosen per keyframe, not per point: the traversals present at the place (a 16 m cell), in
// a rotating order whose start depends on the keyframe, so that all points of one keyframe pair
// with the same few keyframes (the normal equations stay O(partners) blocks per keyframe) and
// consecutive keyframes pair with different traversals (every pair of traversals at a place
// stays coupled). Each try is one lookup in one traversal's index: O(partners) per point,
// whatever the number of traversals there.
template <int D>
void associate(PoseProblem<D>& P, const std::vector<AnchoredPoint>& pts,
               const std::vector<int>& ids, int lsms, const AlignSettings& s) {
  constexpr double kCell = 16.0;  // m, presence cells
  constexpr int kProbes = 3;      // traversals tried per partner slot
  const int n = int(pts.size());
  std::vector<Eigen::Vector3d> world(n);
  for (int i = 0; i < n; ++i) {
    const PoseVar& x = P.poses()[P.poseIndex(pts[i].lsm, pts[i].kf)];
    world[i] = x.q * pts[i].body + x.t;
  }
  // One index per traversal; presence lists per cell.
  std::vector<std::vector<int>> members(lsms);
  for (int i = 0; i < n; ++i) members[pts[i].lsm].push_back(i);
  // Cells of twice the radius: a query then visits at most 2 x 2 x 2 cells (the ones nearer than
  // the radius), not 27.
  const double radius = 2.0 * std::max(0.1, s.gba_association_distance);
  std::vector<VoxelIndex> index(lsms);
  parallelFor(
      std::size_t(lsms),
      [&](std::size_t l) {
        std::vector<Eigen::Vector3d> w;
        w.reserve(members[l].size());
        for (int i : members[l]) w.push_back(world[i]);
        if (!w.empty()) index[l] = VoxelIndex(w, radius);
      },
      s.threads);
  auto cellKey = [&](const Eigen::Vector3d& p) {
    return (uint64_t(uint32_t(int32_t(std::floor(p.x() / kCell)))) << 32) |
           uint32_t(int32_t(std::floor(p.y() / kCell)));
  };
  std::unordered_map<uint64_t, std::vector<int>> present;
  for (int i = 0; i < n; ++i) {
    auto& v = present[cellKey(world[i])];
    if (v.empty() || v.back() != pts[i].lsm) v.push_back(pts[i].lsm);
  }
  for (auto& [key, v] : present) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  }
  const double r2 = s.gba_association_distance * s.gba_association_distance;
  // (point a, point b) per thread; a static schedule gives each thread one contiguous range of
  // points, in thread order: the lists joined in thread order run in point order, whose ids
  // rise with the point (a sort by (a, b) then only has to order each point's few partners).
  std::vector<std::vector<std::pair<int, int>>> found(std::max(1, s.threads));
#pragma omp parallel num_threads(s.threads)
  {
    std::vector<std::pair<int, int>>& local = found[omp_get_thread_num()];
    std::vector<int> others, chosen;
#pragma omp for schedule(static)
    for (int i = 0; i < n; ++i) {
      const auto& here = present.at(cellKey(world[i]));
      others.clear();
      for (int l : here)
        if (l != pts[i].lsm) others.push_back(l);
      const int m = int(others.size());
      if (m == 0) continue;
      const int keep = s.gba_max_partners > 0 ? std::min(m, s.gba_max_partners) : m;
      const int probes = s.gba_max_partners > 0 ? kProbes : 1;
      const int offset = int((uint64_t(pts[i].kf) + 7919ull * uint64_t(pts[i].lsm)) % m);
      chosen.clear();
      for (int t = 0; t < keep; ++t) {
        const int j0 = offset + t * m / keep;
        for (int u = 0; u < probes && u < m; ++u) {
          const int l = others[(j0 + u) % m];
          if (std::find(chosen.begin(), chosen.end(), l) != chosen.end()) continue;
          double d2 = 0;
          const int j = index[l].size() ? index[l].nearest(world[i], r2, &d2) : -1;
          if (j < 0) continue;
          chosen.push_back(l);
          local.emplace_back(ids[i], ids[members[l][j]]);
          break;
        }
      }
    }
  }
  for (auto& list : found) {
    for (std::size_t k = 0; k < list.size();) {  // one point's partners: by partner id
      std::size_t e = k + 1;
      while (e < list.size() && list[e].first == list[k].first) ++e;
      std::sort(list.begin() + k, list.begin() + e);
      k = e;
    }
    for (const auto& [a, b] : list) P.addElementPair(a, b);
  }
}

template <int D>
GraphSolve gba(std::vector<Lsm>& lsms, const std::vector<Lsm>& priors, const AlignSettings& s) {
  const detail::GpsPriorTerms g = detail::gpsPriorTerms(priors, s);
  PoseProblem<D> P = makeProblem<D>(lsms, priors, g);
  addPriorsAndOdometry(P, priors, g, s);
  P.setElementHuber(s.gba_huber);
  // Element points (anchor body frames) and their problem ids, per class; of each point the
  // association keeps only its pose and body point (held through every round).
  std::vector<std::vector<AnchoredPoint>> pts(kNumCrowdClasses);
  std::vector<std::vector<int>> ids(kNumCrowdClasses);
  std::vector<std::size_t> count(kNumCrowdClasses, 0);  // first pass: sizes, for exact vectors
  for (int c = 0; c < kNumCrowdClasses; ++c)
    forEachElementPoint(lsms, CrowdClass(c), s.gba_line_stride,
                        [&](const ElementPoint&) { ++count[c]; });
  P.reserveElementPoints(std::accumulate(count.begin(), count.end(), std::size_t(0)));
  for (int c = 0; c < kNumCrowdClasses; ++c) {
    ids[c].reserve(count[c]);
    pts[c].reserve(count[c]);
    forEachElementPoint(lsms, CrowdClass(c), s.gba_line_stride, [&](const ElementPoint& p) {
      ids[c].push_back(P.addElementPoint(P.poseIndex(p.lsm, p.kf), p.body, p.dir, p.plane,
                                         p.weight / s.gba_point_sigma));
      pts[c].push_back({p.lsm, p.kf, p.body});
    });
  }
  GraphSolve out;
  for (int round = 0; round < std::max(1, s.gba_rounds); ++round) {
    P.clearElementPairs();
    for (int c = 0; c < kNumCrowdClasses; ++c)
      if (!pts[c].empty()) associate(P, pts[c], ids[c], int(lsms.size()), s);
    out.residuals = int(P.elementPairs());
    // Rounds before the last only feed the next association: a looser stop suffices.
    const bool last = round + 1 >= s.gba_rounds;
    const auto r =
        P.solve(problemSettings(s, last ? s.function_tolerance : s.gba_early_round_tolerance));
    addSolve(out, r, keyframeCount(lsms));
    MAPFUSE_DEBUG("align: GBA round "
                  << round << ": " << P.elementPairs() << " residuals, " << r.blocks
                  << " blocks over " << keyframeCount(lsms) << " keyframes, " << r.iterations
                  << " LM / " << r.pcg_iterations << " PCG iterations, cost " << r.initial_cost
                  << " -> " << r.final_cost);
  }
  writeBack(lsms, P);
  return out;
}

}  // namespace

GraphSolve solveMultiPoseGraph(std::vector<Lsm>& lsms, const std::vector<Lsm>& priors,
                               std::vector<InterConstraint>& constraints, const AlignSettings& s) {
  GraphSolve out;
  const detail::GpsPriorTerms g = detail::gpsPriorTerms(priors, s);
  for (int round = 0; round < std::max(1, s.graph_rejection_rounds); ++round) {
    // Later rounds start from the previous solution: only the dropped constraints changed.
    PoseProblem<6> P = makeProblem<6>(lsms, priors, g);
    addPriorsAndOdometry(P, priors, g, s);
    for (const auto& c : constraints) {  // eq. (11), Huber-robust
      if (!c.consistent || c.graph_outlier) continue;
      P.addRelative(P.poseIndex(c.lsm_a, c.kf_a), P.poseIndex(c.lsm_b, c.kf_b), c.T_a_b,
                    sqrtInformation(c.covariance), s.inter_huber);
    }
    const auto r = P.solve(problemSettings(s, s.function_tolerance));
    addSolve(out, r, keyframeCount(lsms));
    MAPFUSE_DEBUG("align: pose graph round " << round << ": " << r.blocks << " blocks, "
                                             << r.iterations << " LM / " << r.pcg_iterations
                                             << " PCG iterations, cost " << r.initial_cost << " -> "
                                             << r.final_cost);
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
  return out;
}

GraphSolve solveGba(std::vector<Lsm>& lsms, const std::vector<Lsm>& priors,
                    const AlignSettings& s) {
  // 4 DOF: roll and pitch are held where georef's gravity prior put them.
  return s.gba_dof == 4 ? gba<4>(lsms, priors, s) : gba<6>(lsms, priors, s);
}

}  // namespace mapfuse::fusion
