#include "mapfuse/fusion/align.hpp"

#include <chrono>

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
  const std::vector<Lsm> priors = lsms;  // georef poses: GPS priors and odometry
  AlignResult r;
  r.method = s.method;
  auto t = Clock::now();
  r.constraints = registerSubmaps(lsms, s);  // eq. (7)
  r.seconds_registration = since(t);
  t = Clock::now();
  r.constraints_pcm_kept = pcmSelect(lsms, r.constraints, s);
  r.seconds_pcm = since(t);
  t = Clock::now();
  r.cost_pose_graph =  // eq. (8)-(11)
      solveMultiPoseGraph(lsms, priors, r.constraints, s, &r.converged_pose_graph);
  r.converged = r.converged_pose_graph;
  r.seconds_pose_graph = since(t);
  if (s.method == AlignMethod::kGbaSgicp) {
    t = Clock::now();
    r.ran_gba = true;  // eq. (12)-(14)
    r.cost_gba = solveGba(lsms, priors, s, &r.gba_residuals, &r.converged_gba);
    r.converged = r.converged_gba;
    r.seconds_gba = since(t);
  }
  for (const auto& c : r.constraints) {
    r.constraints_accepted += c.accepted;
    r.constraints_graph_outliers += c.graph_outlier;
  }
  return r;
}

}  // namespace mapfuse::fusion
