#pragma once
/// @file Stage `align` (§4.2, Song et al. 2023): SGICP + PCM + multi-trajectory pose graph, then
/// GBA, over georeferenced LSMs sharing one ENU origin. `--method` selects the Table 1 baseline.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mapfuse/core/params.hpp"
#include "mapfuse/fusion/align.hpp"

namespace mapfuse::stages {

struct AlignParams {
  std::string method = "gba_sgicp";
  double submap_length = 60.0;
  double min_overlap = 0.3;
  double overlap_radius = 4.0;
  int max_partners = 2;
  std::string partner_choice = "spread";
  double coarse_radius = 8.0;
  double coarse_bin = 0.5;
  double coarse_prior_sigma = 8.0;
  int coarse_neighbors = 1;
  double min_fitness = 0.3;
  double max_rmse = 0.5;
  double min_information = 10.0;
  int max_iterations = 12;
  double pcm_gate = 16.81;
  int pcm_exact_max = 40;
  double odom_sigma_per_m = 0.01;
  double odom_min_sigma = 0.02;
  double prior_rotation_sigma = 0.05;
  double inter_huber = 1.0;
  double constraint_min_sigma = 0.05;
  double constraint_cov_scale = 10.0;
  double graph_reject_chi2 = 100.0;
  int graph_rejection_rounds = 3;
  double gba_association_distance = 0.5;
  double gba_point_sigma = 0.05;
  double gba_huber = 1.0;
  int gba_rounds = 2;
  int gba_max_partners = 2;
  int gba_dof = 4;
  int gba_line_stride = 2;
  int pcg_iterations = 50;
  double gba_early_round_tolerance = 1e-2;
  int solver_iterations = 100;
  double function_tolerance = 1e-2;
  int threads = 2;

  template <class V>
  void visit(V& v) {
    v("method", method, "", "icp | sicp | sgicp | gba_sgicp");
    v("submap_length", submap_length, "m", "keyframe path length per submap");
    v("min_overlap", min_overlap, "", "min share of coarse points near the other submap");
    v("overlap_radius", overlap_radius, "m", "overlap test radius (GPS-level initial error)");
    v("max_partners", max_partners, "", "per submap, register with this many other LSMs (0 = all)");
    v("partner_choice", partner_choice, "",
      "overlap (the best-overlapping LSMs) | spread (an evenly spread subset of the overlapping "
      "LSMs)");
    v("coarse_radius", coarse_radius, "m", "coarse displacement-voting search radius");
    v("coarse_bin", coarse_bin, "m", "coarse displacement histogram bin");
    v("coarse_prior_sigma", coarse_prior_sigma, "m", "Gaussian prior on the coarse shift");
    v("coarse_neighbors", coarse_neighbors, "", "add votes of pairs of submaps this near");
    v("min_fitness", min_fitness, "", "accept registrations with inlier fraction above");
    v("max_rmse", max_rmse, "m", "accept registrations with RMS residual below");
    v("min_information", min_information, "",
      "SGICP leaves directions with less information alone (0: off)");
    v("max_iterations", max_iterations, "", "GICP iterations per pyramid level");
    v("pcm_gate", pcm_gate, "", "chi2 gate of PCM pairwise consistency (6 dof)");
    v("pcm_exact_max", pcm_exact_max, "", "exact maximum clique up to this many constraints");
    v("odom_sigma_per_m", odom_sigma_per_m, "m/m", "relative odometry sigma per metre");
    v("odom_min_sigma", odom_min_sigma, "m", "odometry sigma floor");
    v("prior_rotation_sigma", prior_rotation_sigma, "rad", "GPS prior sigma on attitude");
    v("inter_huber", inter_huber, "sigma", "Huber delta on inter-trajectory factors");
    v("constraint_min_sigma", constraint_min_sigma, "m", "floor of an InterRPC translation sigma");
    v("constraint_cov_scale", constraint_cov_scale, "", "inflation of the GICP inverse Hessian");
    v("graph_reject_chi2", graph_reject_chi2, "", "drop InterRPCs this far off the graph solution");
    v("graph_rejection_rounds", graph_rejection_rounds, "", "pose-graph solve / reject rounds");
    v("gba_association_distance", gba_association_distance, "m", "GBA association radius");
    v("gba_point_sigma", gba_point_sigma, "m", "GBA point-to-line/plane sigma");
    v("gba_huber", gba_huber, "sigma", "Huber delta on GBA residuals");
    v("gba_rounds", gba_rounds, "", "GBA association / solve rounds");
    v("gba_max_partners", gba_max_partners, "",
      "other traversals each element point is tied to (0 = all)");
    v("gba_dof", gba_dof, "",
      "GBA pose freedom: 4 (x, y, z, yaw; roll and pitch held from georef) or 6");
    v("gba_line_stride", gba_line_stride, "",
      "GBA uses every n-th point of a line element, weighted by sqrt(n)");
    v("pcg_iterations", pcg_iterations, "",
      "conjugate-gradient iterations per Levenberg-Marquardt step (pose graph and GBA)");
    v("gba_early_round_tolerance", gba_early_round_tolerance, "",
      "LM stop (relative cost change) of the GBA rounds before the last");
    v("solver_iterations", solver_iterations, "", "Levenberg-Marquardt iterations per solve");
    v("function_tolerance", function_tolerance, "", "LM stop: relative cost change below");
    v("threads", threads, "", "OpenMP threads over pairs / Ceres threads");
  }
  void validate() const;
  fusion::AlignSettings settings() const;
};

/// @brief Aligns the LSMs; writes each to <out_dir>/<same file name>, align.config.json and
/// align.summary.json. @return the summary.
/// @throws InputError when an LSM is not in enu or origins differ; IoError / ParseError.
nlohmann::json runAlign(const std::vector<std::string>& inputs,
                        const std::filesystem::path& out_dir, const AlignParams& params);

/// @brief The algorithm without files: aligns `lsms` in place. @return the summary JSON.
nlohmann::json alignInPlace(std::vector<Lsm>& lsms, const fusion::AlignSettings& s);

}  // namespace mapfuse::stages
