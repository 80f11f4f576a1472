#include "mapfuse/stages/align.hpp"

#include <chrono>
#include <cmath>

#include "mapfuse/cli/params.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/io/lsm_io.hpp"
#include "mapfuse/io/output_transaction.hpp"
#include "mapfuse/io/stage_report.hpp"

namespace mapfuse::stages {
namespace {

/// One solve's figures under the summary's keys: cost_<name>, converged_<name>,
/// <name>_iterations, <name>_pcg_iterations, seconds_<name>.
void writeSolve(nlohmann::json& sum, const std::string& name, const fusion::GraphSolve& g,
                double seconds) {
  sum["cost_" + name] = g.cost;
  sum["converged_" + name] = g.converged;
  sum[name + "_iterations"] = g.iterations;
  sum[name + "_pcg_iterations"] = g.pcg_iterations;
  sum["seconds_" + name] = seconds;
}

/// Tie statistics: the stretches by tied traversals (0 .. 9, "10+"), median, share tied to none.
nlohmann::json tiesJson(const fusion::TieStatistics& t) {
  nlohmann::json hist = nlohmann::json::object();
  for (int n : t.tied) {
    const std::string key = n >= 10 ? "10+" : std::to_string(n);
    hist[key] = hist.value(key, 0) + 1;
  }
  return {{"stretch_m", t.stretch_m},          {"stretches", t.tied.size()},
          {"by_tied_traversals", hist},        {"median_tied_traversals", t.median()},
          {"untied_share", t.untiedShare()}};
}

}  // namespace

nlohmann::json toJson(const fusion::AlignResult& r) {
  nlohmann::json sum;
  sum["seconds_registration"] = r.seconds_registration;
  sum["seconds_pcm"] = r.seconds_pcm;
  writeSolve(sum, "pose_graph", r.pose_graph, r.seconds_pose_graph);
  sum["pose_graph_solves"] = r.pose_graph.rounds;
  if (r.ran_gba) {
    writeSolve(sum, "gba", r.gba, r.seconds_gba);
    sum["gba_residuals"] = r.gba.residuals;
  }
  sum["constraints_graph_outliers"] = r.constraints_graph_outliers;
  nlohmann::json pairs = nlohmann::json::array();
  for (const auto& c : r.constraints)
    pairs.push_back({{"lsm_a", c.lsm_a},
                     {"kf_a", c.kf_a},
                     {"lsm_b", c.lsm_b},
                     {"kf_b", c.kf_b},
                     {"overlap", c.overlap},
                     {"fitness", c.fitness},
                     {"rmse_m", c.rmse},
                     {"iterations", c.iterations},
                     {"converged", c.converged},
                     {"accepted", c.accepted},
                     {"pcm_consistent", c.consistent},
                     {"graph_outlier", c.graph_outlier},
                     {"graph_chi2", c.graph_chi2}});
  sum["method"] = fusion::alignMethodName(r.method);
  sum["pairs"] = pairs;
  sum["constraints_proposed"] = r.constraints.size();
  sum["constraints_accepted"] = r.constraints_accepted;
  sum["constraints_pcm_kept"] = r.constraints_pcm_kept;
  sum["ties"] = tiesJson(r.ties);
  sum["converged"] = r.converged;
  return sum;
}

fusion::AlignResult runAlign(const std::vector<std::string>& inputs,
                             const std::filesystem::path& out_dir, const AlignParams& params) {
  const auto t0 = std::chrono::steady_clock::now();
  validateParams(params);
  io::OutputTransaction outputs(out_dir);  // locked and writable before the work
  if (inputs.empty()) throw InputError("align: no input LSM");
  // Without the per-point covariances (align does not read them; three quarters of a decoded
  // LSM): each input is read whole again when its output is written.
  std::vector<Lsm> lsms = io::readLsmInputs(inputs, /*covariances=*/false);
  for (std::size_t i = 0; i < lsms.size(); ++i) {
    const Lsm& l = lsms[i];
    const std::string& in = inputs[i];
    if (l.frame != LsmFrame::kEnu || !l.origin)
      throw InputError(in + ": frame must be enu (run georef first)");
    const auto& o0 = *lsms.front().origin;
    if (l.origin->lat != o0.lat || l.origin->lon != o0.lon || l.origin->alt != o0.alt)
      throw InputError(in + ": origin differs from " + inputs.front() + " (one shared origin)");
    if (l.keyframes.empty()) throw InputError(in + ": LSM has no keyframes");
  }
  const fusion::AlignResult result = fusion::alignLsms(lsms, params.align);
  io::writeWithKeyframes(inputs, lsms, out_dir);  // the inputs with the aligned keyframes
  nlohmann::json summary = toJson(result);
  summary["inputs"] = inputs;
  summary["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  MAPFUSE_INFO("align: " << result.constraints.size() << " constraints proposed, "
                         << result.constraints_pcm_kept << " kept by PCM; "
                         << result.ties.median() << " other traversals tied to the median "
                         << fusion::kTieStretch << " m stretch, "
                         << std::round(1000.0 * result.ties.untiedShare()) / 10.0
                         << " % tied to none");
  io::writeResolvedConfig(out_dir, "align", paramsToJson(params));
  io::writeSummary(out_dir, "align", summary);
  outputs.commit();
  return result;
}

}  // namespace mapfuse::stages
