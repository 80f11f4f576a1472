#include "mapfuse/stages/align.hpp"

#include <chrono>

#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/io/lsm_io.hpp"
#include "mapfuse/io/stage_report.hpp"

namespace mapfuse::stages {

void AlignParams::validate() const {
  const char* st = "AlignParams";
  requireParam(fusion::alignMethodFromName(method).has_value(), st, "method", method,
               "one of icp, sicp, sgicp, gba_sgicp");
  requireParam(submap_length > 0, st, "submap_length", submap_length, "> 0");
  requireParam(min_overlap >= 0 && min_overlap <= 1, st, "min_overlap", min_overlap, "in [0, 1]");
  requireParam(overlap_radius > 0, st, "overlap_radius", overlap_radius, "> 0");
  requireParam(max_partners >= 0, st, "max_partners", max_partners, ">= 0");
  requireParam(partner_choice == "overlap" || partner_choice == "spread", st, "partner_choice",
               partner_choice, "overlap or spread");
  requireParam(coarse_radius > 0, st, "coarse_radius", coarse_radius, "> 0");
  requireParam(coarse_bin > 0 && coarse_bin < coarse_radius, st, "coarse_bin", coarse_bin,
               "in (0, coarse_radius)");
  requireParam(coarse_prior_sigma > 0, st, "coarse_prior_sigma", coarse_prior_sigma, "> 0");
  requireParam(coarse_neighbors >= 0, st, "coarse_neighbors", coarse_neighbors, ">= 0");
  requireParam(constraint_min_sigma > 0, st, "constraint_min_sigma", constraint_min_sigma, "> 0");
  requireParam(constraint_cov_scale > 0, st, "constraint_cov_scale", constraint_cov_scale, "> 0");
  requireParam(graph_reject_chi2 > 0, st, "graph_reject_chi2", graph_reject_chi2, "> 0");
  requireParam(graph_rejection_rounds >= 1, st, "graph_rejection_rounds", graph_rejection_rounds,
               ">= 1");
  requireParam(min_fitness >= 0 && min_fitness <= 1, st, "min_fitness", min_fitness, "in [0, 1]");
  requireParam(max_rmse > 0, st, "max_rmse", max_rmse, "> 0");
  requireParam(min_information >= 0, st, "min_information", min_information, ">= 0");
  requireParam(max_iterations >= 1, st, "max_iterations", max_iterations, ">= 1");
  requireParam(pcm_gate > 0, st, "pcm_gate", pcm_gate, "> 0");
  requireParam(pcm_exact_max >= 0, st, "pcm_exact_max", pcm_exact_max, ">= 0");
  requireParam(odom_sigma_per_m >= 0, st, "odom_sigma_per_m", odom_sigma_per_m, ">= 0");
  requireParam(odom_min_sigma > 0, st, "odom_min_sigma", odom_min_sigma, "> 0");
  requireParam(prior_rotation_sigma > 0, st, "prior_rotation_sigma", prior_rotation_sigma, "> 0");
  requireParam(inter_huber > 0, st, "inter_huber", inter_huber, "> 0");
  requireParam(gba_association_distance > 0, st, "gba_association_distance",
               gba_association_distance, "> 0");
  requireParam(gba_point_sigma > 0, st, "gba_point_sigma", gba_point_sigma, "> 0");
  requireParam(gba_huber > 0, st, "gba_huber", gba_huber, "> 0");
  requireParam(gba_rounds >= 1, st, "gba_rounds", gba_rounds, ">= 1");
  requireParam(gba_max_partners >= 0, st, "gba_max_partners", gba_max_partners, ">= 0");
  requireParam(gba_dof == 4 || gba_dof == 6, st, "gba_dof", gba_dof, "4 or 6");
  requireParam(gba_line_stride >= 1, st, "gba_line_stride", gba_line_stride, ">= 1");
  requireParam(pcg_iterations >= 1, st, "pcg_iterations", pcg_iterations, ">= 1");
  requireParam(gba_early_round_tolerance > 0 && gba_early_round_tolerance < 1, st,
               "gba_early_round_tolerance", gba_early_round_tolerance, "in (0, 1)");
  requireParam(function_tolerance > 0 && function_tolerance < 1, st, "function_tolerance",
               function_tolerance, "in (0, 1)");
  requireParam(solver_iterations >= 1, st, "solver_iterations", solver_iterations, ">= 1");
  requireParam(threads >= 1, st, "threads", threads, ">= 1");
}

fusion::AlignSettings AlignParams::settings() const {
  fusion::AlignSettings s;
  s.method = *fusion::alignMethodFromName(method);
  s.submap_length = submap_length;
  s.min_overlap = min_overlap;
  s.overlap_radius = overlap_radius;
  s.max_partners = max_partners;
  s.spread_partners = partner_choice == "spread";
  s.coarse_radius = coarse_radius;
  s.coarse_bin = coarse_bin;
  s.coarse_prior_sigma = coarse_prior_sigma;
  s.coarse_neighbors = coarse_neighbors;
  s.constraint_min_sigma = constraint_min_sigma;
  s.constraint_cov_scale = constraint_cov_scale;
  s.graph_reject_chi2 = graph_reject_chi2;
  s.graph_rejection_rounds = graph_rejection_rounds;
  s.min_fitness = min_fitness;
  s.max_rmse = max_rmse;
  s.min_information = min_information;
  s.max_iterations = max_iterations;
  s.pcm_gate = pcm_gate;
  s.pcm_exact_max = pcm_exact_max;
  s.odom_sigma_per_m = odom_sigma_per_m;
  s.odom_min_sigma = odom_min_sigma;
  s.prior_rotation_sigma = prior_rotation_sigma;
  s.inter_huber = inter_huber;
  s.gba_association_distance = gba_association_distance;
  s.gba_point_sigma = gba_point_sigma;
  s.gba_huber = gba_huber;
  s.gba_rounds = gba_rounds;
  s.gba_max_partners = gba_max_partners;
  s.gba_dof = gba_dof;
  s.gba_line_stride = gba_line_stride;
  s.pcg_iterations = pcg_iterations;
  s.gba_early_round_tolerance = gba_early_round_tolerance;
  s.function_tolerance = function_tolerance;
  s.solver_iterations = solver_iterations;
  s.threads = threads;
  return s;
}

nlohmann::json alignInPlace(std::vector<Lsm>& lsms, const fusion::AlignSettings& s) {
  using Clock = std::chrono::steady_clock;
  auto since = [](Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
  };
  // The georeferenced keyframes (GPS priors and odometry of eq. (9)-(10)); elements not copied.
  std::vector<Lsm> priors(lsms.size());
  for (std::size_t i = 0; i < lsms.size(); ++i) priors[i].keyframes = lsms[i].keyframes;
  nlohmann::json sum;
  auto t = Clock::now();
  std::vector<fusion::InterConstraint> cs = fusion::registerSubmaps(lsms, s);
  sum["seconds_registration"] = since(t);
  t = Clock::now();
  const int kept = fusion::pcmSelect(lsms, cs, s);
  sum["seconds_pcm"] = since(t);
  t = Clock::now();
  const fusion::GraphSolve pg = fusion::solveMultiPoseGraph(lsms, priors, cs, s);
  bool conv = pg.converged;
  sum["cost_pose_graph"] = pg.cost;
  sum["converged_pose_graph"] = pg.converged;
  sum["pose_graph_solves"] = pg.rounds;
  sum["pose_graph_iterations"] = pg.iterations;
  sum["pose_graph_pcg_iterations"] = pg.pcg_iterations;
  sum["seconds_pose_graph"] = since(t);
  if (s.method == fusion::AlignMethod::kGbaSgicp) {
    t = Clock::now();
    const fusion::GraphSolve g = fusion::solveGba(lsms, priors, s);
    conv = g.converged;
    sum["cost_gba"] = g.cost;
    sum["gba_residuals"] = g.residuals;
    sum["converged_gba"] = g.converged;
    sum["gba_iterations"] = g.iterations;
    sum["gba_pcg_iterations"] = g.pcg_iterations;
    sum["seconds_gba"] = since(t);
  }
  int accepted = 0, graph_outliers = 0;
  for (const auto& c : cs) graph_outliers += c.graph_outlier;
  sum["constraints_graph_outliers"] = graph_outliers;
  nlohmann::json pairs = nlohmann::json::array();
  for (const auto& c : cs) {
    accepted += c.accepted;
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
  }
  sum["method"] = fusion::alignMethodName(s.method);
  sum["pairs"] = pairs;
  sum["constraints_proposed"] = cs.size();
  sum["constraints_accepted"] = accepted;
  sum["constraints_pcm_kept"] = kept;
  sum["converged"] = conv;
  return sum;
}

nlohmann::json runAlign(const std::vector<std::string>& inputs,
                        const std::filesystem::path& out_dir, const AlignParams& params) {
  const auto t0 = std::chrono::steady_clock::now();
  params.validate();
  if (inputs.empty()) throw InputError("align: no input LSM");
  std::vector<Lsm> lsms;
  for (const auto& in : inputs) {
    lsms.push_back(io::readLsm(in));
    const Lsm& l = lsms.back();
    if (l.frame != LsmFrame::kEnu || !l.origin)
      throw InputError(in + ": frame must be enu (run georef first)");
    const auto& o0 = *lsms.front().origin;
    if (l.origin->lat != o0.lat || l.origin->lon != o0.lon || l.origin->alt != o0.alt)
      throw InputError(in + ": origin differs from " + inputs.front() + " (one shared origin)");
    if (l.keyframes.empty()) throw InputError(in + ": LSM has no keyframes");
  }
  nlohmann::json summary = alignInPlace(lsms, params.settings());
  std::filesystem::create_directories(out_dir);
  for (std::size_t i = 0; i < lsms.size(); ++i)
    io::writeLsm(out_dir / std::filesystem::path(inputs[i]).filename(), lsms[i]);
  summary["inputs"] = inputs;
  summary["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  MAPFUSE_INFO("align: " << summary["constraints_proposed"] << " constraints proposed, "
                         << summary["constraints_pcm_kept"] << " kept by PCM");
  io::writeResolvedConfig(out_dir, "align", paramsToJson(params));
  io::writeSummary(out_dir, "align", summary);
  return summary;
}

}  // namespace mapfuse::stages
