#include "mapfuse/fusion/align.hpp"

#include <chrono>

#include "mapfuse/core/heap.hpp"

namespace mapfuse::fusion {

const param::Names<AlignMethod>& alignMethodNames() {
  static const param::Names<AlignMethod> names{{{"icp", AlignMethod::kIcp},
                                                {"sicp", AlignMethod::kSicp},
                                                {"sgicp", AlignMethod::kSgicp},
                                                {"gba_sgicp", AlignMethod::kGbaSgicp}}};
  return names;
}

std::optional<AlignMethod> alignMethodFromName(const std::string& name) {
  AlignMethod m;
  if (!alignMethodNames().find(name, &m)) return std::nullopt;
  return m;
}

const char* alignMethodName(AlignMethod m) {
  return alignMethodNames().nameOf(m);
}

AlignResult alignLsms(std::vector<Lsm>& lsms, const AlignSettings& s) {
  using Clock = std::chrono::steady_clock;
  auto since = [](Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
  };
  // The georeferenced keyframes (GPS priors and odometry of eq. (9)-(10)); elements not copied.
  std::vector<Lsm> priors(lsms.size());
  for (std::size_t i = 0; i < lsms.size(); ++i) priors[i].keyframes = lsms[i].keyframes;
  AlignResult r;
  r.method = s.method;
  auto t = Clock::now();
  r.constraints = registerSubmaps(lsms, s);  // eq. (7)
  r.seconds_registration = since(t);
  // The submaps, built on all threads, are gone: their memory back (20 km x 50: 1033 -> 997 MiB).
  releaseFreeHeap();
  t = Clock::now();
  r.constraints_pcm_kept = pcmSelect(lsms, r.constraints, s);
  r.seconds_pcm = since(t);
  t = Clock::now();
  r.pose_graph = solveMultiPoseGraph(lsms, priors, r.constraints, s);  // eq. (8)-(11)
  r.converged = r.pose_graph.converged;
  r.seconds_pose_graph = since(t);
  if (s.method == AlignMethod::kGbaSgicp) {
    t = Clock::now();
    r.ran_gba = true;
    r.gba = solveGba(lsms, priors, s);  // eq. (12)-(14)
    r.converged = r.gba.converged;
    r.seconds_gba = since(t);
  }
  for (const auto& c : r.constraints) {
    r.constraints_accepted += c.accepted;
    r.constraints_graph_outliers += c.graph_outlier;
  }
  r.ties = tieStatistics(lsms, r.constraints, kTieStretch);
  return r;
}

}  // namespace mapfuse::fusion
