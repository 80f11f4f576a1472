// Pairwise consistency maximization (Mangelson et al. 2018) over InterRPCs.
#include <algorithm>
#include <functional>
#include <map>

#include "graph_covariances.hpp"
#include "mapfuse/fusion/align.hpp"

namespace mapfuse::fusion {

std::vector<int> maximumClique(const std::vector<std::vector<char>>& adj, int exact_max) {
  const int n = int(adj.size());
  std::vector<int> best;
  if (n == 0) return best;
  if (n <= exact_max) {
    // Branch and bound: extend `clique` with candidates in increasing order.
    std::vector<int> clique;
    std::function<void(std::vector<int>)> expand = [&](std::vector<int> cand) {
      if (clique.size() > best.size()) best = clique;
      while (!cand.empty()) {
        if (clique.size() + cand.size() <= best.size()) return;  // bound
        const int v = cand.front();
        cand.erase(cand.begin());
        std::vector<int> next;
        for (int u : cand)
          if (adj[v][u]) next.push_back(u);
        clique.push_back(v);
        expand(next);
        clique.pop_back();
      }
    };
    std::vector<int> all(n);
    for (int i = 0; i < n; ++i) all[i] = i;
    expand(all);
  } else {
    // Greedy: vertices by decreasing degree, kept when adjacent to all kept so far.
    std::vector<int> order(n), degree(n, 0);
    for (int i = 0; i < n; ++i) {
      order[i] = i;
      for (int j = 0; j < n; ++j) degree[i] += adj[i][j] != 0;
    }
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return degree[a] > degree[b]; });
    for (int v : order)
      if (std::all_of(best.begin(), best.end(), [&](int u) { return adj[v][u] != 0; }))
        best.push_back(v);
  }
  std::sort(best.begin(), best.end());
  return best;
}

int pcmSelect(const std::vector<Lsm>& lsms, std::vector<InterConstraint>& cs,
              const AlignSettings& s) {
  // Group accepted constraints by LSM pair; constraints of different pairs share no cycle here.
  std::map<std::pair<int, int>, std::vector<int>> groups;
  for (int i = 0; i < int(cs.size()); ++i) {
    cs[i].consistent = false;
    if (cs[i].accepted) groups[{cs[i].lsm_a, cs[i].lsm_b}].push_back(i);
  }
  // The odometry legs of a cycle have the covariance the pose graph gives the same odometry
  // (eq. 10, graph_covariances.hpp): one noise model for the consistency test and the solve.
  auto odomCov = [&](const Pose3& T) { return detail::odometryCovariance(T, s); };
  int kept = 0;
  for (const auto& [key, idx] : groups) {
    const int n = int(idx.size());
    std::vector<std::vector<char>> adj(n, std::vector<char>(n, 0));
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j) {
        const InterConstraint& k = cs[idx[i]];
        const InterConstraint& l = cs[idx[j]];
        const auto& A = lsms[key.first].keyframes;
        const auto& B = lsms[key.second].keyframes;
        // cycle a1 -> a2 (odometry A) -> b2 (constraint l) -> b1 (odometry B) vs constraint k
        const Pose3 T_a1_a2 = A[k.kf_a].T_frame_body.inverse() * A[l.kf_a].T_frame_body;
        const Pose3 T_b2_b1 = B[l.kf_b].T_frame_body.inverse() * B[k.kf_b].T_frame_body;
        const Pose3 pred = T_a1_a2 * l.T_a_b * T_b2_b1;
        const Vector6d e = logSE3(k.T_a_b.inverse() * pred);
        const Matrix6d C = k.covariance + l.covariance + odomCov(T_a1_a2) + odomCov(T_b2_b1);
        const double chi2 = e.dot(C.ldlt().solve(e));
        adj[i][j] = adj[j][i] = chi2 < s.pcm_gate;
      }
    for (int v : maximumClique(adj, s.pcm_exact_max)) {
      cs[idx[v]].consistent = true;
      ++kept;
    }
  }
  return kept;
}

}  // namespace mapfuse::fusion
