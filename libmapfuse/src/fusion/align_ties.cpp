// How many other traversals the kept registrations tie each stretch of road to (align.hpp).
#include <algorithm>
#include <set>

#include "mapfuse/fusion/align.hpp"

namespace mapfuse::fusion {

TieStatistics tieStatistics(const std::vector<Lsm>& lsms,
                            const std::vector<InterConstraint>& constraints, double stretch_m) {
  // Stretch of every keyframe: its distance along its traversal's path over stretch_m.
  std::vector<std::vector<int>> stretch(lsms.size());
  std::vector<int> first(lsms.size() + 1, 0);  // index of each traversal's first stretch
  for (std::size_t l = 0; l < lsms.size(); ++l) {
    const auto& kfs = lsms[l].keyframes;
    double dist = 0;
    for (std::size_t k = 0; k < kfs.size(); ++k) {
      if (k > 0)
        dist += (kfs[k].T_frame_body.translation() - kfs[k - 1].T_frame_body.translation()).norm();
      stretch[l].push_back(int(dist / stretch_m));
    }
    first[l + 1] = first[l] + (kfs.empty() ? 0 : stretch[l].back() + 1);
  }
  std::vector<std::set<int>> partners(first.back());
  for (const auto& c : constraints) {
    if (!c.accepted || !c.consistent || c.graph_outlier) continue;
    partners[first[c.lsm_a] + stretch[c.lsm_a][c.kf_a]].insert(c.lsm_b);
    partners[first[c.lsm_b] + stretch[c.lsm_b][c.kf_b]].insert(c.lsm_a);
  }
  TieStatistics t;
  t.stretch_m = stretch_m;
  for (const auto& p : partners) t.tied.push_back(int(p.size()));
  return t;
}

int TieStatistics::median() const {
  if (tied.empty()) return 0;
  std::vector<int> sorted = tied;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  return sorted[sorted.size() / 2];
}

double TieStatistics::untiedShare() const {
  if (tied.empty()) return 0.0;
  return double(std::count(tied.begin(), tied.end(), 0)) / double(tied.size());
}

}  // namespace mapfuse::fusion
