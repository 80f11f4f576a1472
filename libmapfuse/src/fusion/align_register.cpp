// Stage 1 registrations (eq. (7), Song et al. 2023): submaps, semantic pyramid, InterRPCs.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

#include "align_internal.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/fusion/align.hpp"
#include "mapfuse/fusion/gicp.hpp"

namespace mapfuse::fusion {

namespace {
constexpr int kSourceSolidStride = 2;
}  // namespace

std::vector<InterConstraint> registerSubmaps(const std::vector<Lsm>& lsms, const AlignSettings& s) {
  using namespace detail;
  auto dbg_t0 = std::chrono::steady_clock::now();
  auto dbg = [&](const char* what) {
    const auto t = std::chrono::steady_clock::now();
    MAPFUSE_DEBUG("align: registration, "
                  << what << " " << std::chrono::duration<double>(t - dbg_t0).count() << " s");
    dbg_t0 = t;
  };
  const std::vector<Submap> maps = buildSubmaps(lsms, s.submap_length, s.threads);
  dbg("submaps");
  const std::vector<SubmapPair> pairs = selectPairs(maps, s);
  dbg("pairs");
  const bool semantic = s.method != AlignMethod::kIcp;
  const bool gicp = s.method == AlignMethod::kSgicp || s.method == AlignMethod::kGbaSgicp;
  const std::vector<double> weights = labelWeights(s.class_weights);
  std::vector<InterConstraint> out(pairs.size());
  // Coarse level: displacement votes per pair, summed with the votes of the pairs of adjacent
  // submaps of the same two LSMs (their relative GPS error is nearly the same; more road
  // directions and landmarks remove lane and dash aliases).
  std::vector<DisplacementVotes> votes(gicp ? pairs.size() : 0);
  const std::vector<double> vw = coarseVoteWeights(s);
#pragma omp parallel for schedule(dynamic) num_threads(s.threads)
  for (int p = 0; p < int(votes.size()); ++p)
    votes[p] = voteDisplacements(maps[pairs[p].a].coarse, maps[pairs[p].b].coarse, vw,
                                 s.coarse_radius, s.coarse_bin);
  dbg("votes");
  std::map<std::pair<int, int>, int> pair_index;
  for (int p = 0; p < int(pairs.size()); ++p) pair_index[{pairs[p].a, pairs[p].b}] = p;
#pragma omp parallel for schedule(dynamic) num_threads(s.threads)
  for (int p = 0; p < int(pairs.size()); ++p) {
    const Submap& A = maps[pairs[p].a];
    const Submap& B = maps[pairs[p].b];
    InterConstraint& c = out[p];
    c.lsm_a = A.lsm;
    c.kf_a = A.anchor;
    c.lsm_b = B.lsm;
    c.kf_b = B.anchor;
    c.overlap = pairs[p].overlap;
    Pose3 delta = Pose3::Identity();  // maps B's ENU points onto A's
    if (gicp) {
      // Coarsest level of the semantic pyramid: displacement voting (align_coarse.cpp).
      DisplacementVotes sum = votes[p];
      for (int da = -s.coarse_neighbors; da <= s.coarse_neighbors; ++da)
        for (int db = -s.coarse_neighbors; db <= s.coarse_neighbors; ++db) {
          const int a2 = pairs[p].a + da, b2 = pairs[p].b + db;
          if ((da == 0 && db == 0) || a2 < 0 || b2 < 0 || a2 >= int(maps.size()) ||
              b2 >= int(maps.size()) || maps[a2].lsm != A.lsm || maps[b2].lsm != B.lsm)
            continue;
          const auto it = pair_index.find({a2, b2});
          if (it != pair_index.end()) sum.add(votes[it->second], 0.5);
        }
      const DisplacementPeak cr = votePeak(sum, s.coarse_prior_sigma);
      delta.translation().head<2>() = cr.t;
    }
    // Target: every point; source: every 2nd point of solid lane lines (0.75 m apart in the
    // LSMs, free along the line: a neighbour adds little), which halves the GICP work.
    const Cloud a_cloud = submapCloud(lsms, A), b_cloud = submapCloud(lsms, B, kSourceSolidStride);
    GicpResult r;
    for (double dist : s.pyramid_distances) {
      GicpSettings g;
      g.max_correspondence_distance = dist;
      g.max_iterations = s.max_iterations;
      // Converged at 1 mm / 1 mrad steps by default: registrations feed a pose graph and GBA,
      // and 0.1 mm (the GICP default) cost a third more iterations for the same maps.
      g.translation_eps = g.rotation_eps = s.gicp_step_eps;
      g.same_label_only = semantic;
      g.point_to_point = !gicp;
      g.lambda = s.gicp_lambda;
      g.huber_delta = gicp ? s.gicp_huber : 0.0;
      if (gicp) {
        g.label_weights = weights;
        g.min_information = s.min_information;
      }
      const GicpTarget target(a_cloud, 2.0 * dist);  // <= 8 of the 27 cells per query
      GicpResult lr = alignGicp(target, b_cloud, delta, g);
      if (lr.num_inliers >= g.min_inliers) delta = lr.T_target_source;
      c.iterations += lr.iterations;
      r = lr;
    }
    c.converged = r.converged;
    c.fitness = r.fitness;
    c.rmse = r.rmse;
    c.accepted = r.converged && r.fitness >= s.min_fitness && r.rmse <= s.max_rmse;
    // InterRPC: T_a_b = T_enu_a^-1 * delta * T_enu_b. Covariance: the inverse Hessian (delta's
    // right perturbation = perturbation of B's points in ENU... moved to body b by the adjoint),
    // inflated for the per-element correlated noise the per-point model ignores, with a floor.
    const Pose3& Ta = lsms[A.lsm].keyframes[A.anchor].T_frame_body;
    const Pose3& Tb = lsms[B.lsm].keyframes[B.anchor].T_frame_body;
    c.T_a_b = Ta.inverse() * delta * Tb;
    Matrix6d H = r.hessian;
    H.diagonal().array() += 1e-6;
    const double scale =
        gicp ? s.constraint_cov_scale * std::max(1.0, r.error / std::max(1, r.num_inliers - 6))
             : r.rmse * r.rmse + 1e-4;
    Matrix6d cov = H.inverse() * scale;
    const Matrix6d Ad = adjoint(Tb.inverse());
    cov = Ad * cov * Ad.transpose();
    cov += diagonalCovariance(s.constraint_min_sigma, 0.1 * s.constraint_min_sigma);
    c.covariance = 0.5 * (cov + cov.transpose());
  }
  dbg("gicp");
  return out;
}

}  // namespace mapfuse::fusion
