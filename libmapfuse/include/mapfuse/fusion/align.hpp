#pragma once
/// @file Multi-traversal alignment (§4.2, Song et al. 2023): SGICP between overlapping submaps of
/// different traversals (eq. (7)), PCM outlier rejection (Mangelson et al. 2018), the
/// multi-trajectory pose graph (eq. (8)-(11)) and global bundle adjustment GBA (eq. (12)-(14)).
#include <optional>
#include <string>
#include <vector>

#include "mapfuse/core/lsm.hpp"
#include "mapfuse/core/param.hpp"
#include "mapfuse/fusion/point_cloud.hpp"

namespace mapfuse::fusion {

/// Registration flavour (paper Table 1 baselines).
enum class AlignMethod {
  kIcp,       ///< point-to-point ICP, no semantics, + pose graph
  kSicp,      ///< point-to-point ICP within classes, + pose graph
  kSgicp,     ///< semantic GICP with class pyramid and weights, + pose graph (stage 1)
  kGbaSgicp,  ///< stage 1 then GBA (stage 2)
};
std::optional<AlignMethod> alignMethodFromName(const std::string& name);
const char* alignMethodName(AlignMethod m);
/// Config and command-line names of the methods.
const param::Names<AlignMethod>& alignMethodNames();

/// Parameters of align (docs/fusion.md); each declared once, in visit().
struct AlignSettings {
  AlignMethod method = AlignMethod::kGbaSgicp;
  double submap_length = 60.0;  ///< m of keyframe path per submap
  double min_overlap =
      0.3;  ///< share of coarse points with a same-label point within overlap_radius
  double overlap_radius = 4.0;  ///< m, overlap test radius (covers the GPS-level initial error)
  int max_partners = 2;         ///< per submap, register with the best submaps of this many LSMs
  bool spread_partners = true;  ///< choose them evenly spread over the overlapping LSMs instead
  double coarse_radius = 8.0;   ///< m, displacement-voting search radius (coarse level)
  double coarse_bin = 0.5;      ///< m, displacement histogram bin
  double coarse_prior_sigma = 8.0;  ///< m, Gaussian prior on the relative shift (GPS level)
  int coarse_neighbors = 1;         ///< votes of pairs of submaps this many steps away are added
  /// vote weight per coarse (1 m) point by CrowdClass: landmarks count like metres of line
  std::vector<double> coarse_class_weights = {1.0, 3.0, 3.0, 1.0, 10.0, 10.0, 10.0};
  std::vector<double> pyramid_distances = {1.5, 0.75};  ///< m, max correspondence per GICP level
  double gicp_step_eps = 1e-3;  ///< m / rad: a GICP level has converged at steps below this
  double gicp_lambda = 1e-3;    ///< Levenberg damping of the GICP normal equations
  double gicp_huber = 3.0;      ///< sigma, Huber delta on whitened GICP residuals (SGICP, GICP)
  double constraint_min_sigma = 0.05;  ///< m, floor of an InterRPC translation sigma
  double constraint_cov_scale = 10.0;  ///< inflation of H^-1 (correlated element noise)
  std::vector<double> class_weights = {1.0, 1.0, 1.0, 1.0, 2.0, 2.0, 2.0};  ///< w_l by CrowdClass
  double min_fitness = 0.3;               ///< accept a registration above this inlier fraction
  double max_rmse = 0.5;                  ///< m, and below this RMS residual
  double min_information = 10.0;          ///< SGICP: Hessian directions below this are unobservable
  int max_iterations = 12;                ///< per pyramid level
  double pcm_gate = 16.81;                ///< chi2 (6 dof, 99%) of pairwise cycle consistency
  int pcm_exact_max = 40;                 ///< exact maximum clique up to this many constraints
  double odom_sigma_per_m = 0.01;         ///< relative odometry sigma per metre (pose graph, PCM)
  double odom_min_sigma = 0.02;           ///< m / rad floor
  double prior_rotation_sigma = 0.05;     ///< rad, GPS prior on attitude (eq. 9)
  /// GPS bias per traversal (src/fusion/gps_bias.hpp): eq. (9)'s priors are relative to a bias
  /// that walks slowly along the drive, so that registrations move a traversal's bias, not one
  /// keyframe. 0 disables it (independent priors per keyframe).
  double gps_bias_sigma = 2.5;           ///< m, horizontal bias at the start of a traversal
  double gps_bias_vertical_sigma = 5.0;  ///< m, vertical bias at the start
  double gps_bias_walk = 0.05;           ///< m/sqrt(s), random walk of the bias per axis
  double gps_bias_interval = 10.0;       ///< s, between bias nodes (linear in between)
  double inter_huber = 1.0;               ///< Huber delta on whitened inter-trajectory residuals
  double graph_reject_chi2 = 100.0;       ///< drop InterRPCs this far off the graph solution
  int graph_rejection_rounds = 3;         ///< pose-graph solves (reject, re-solve)
  double gba_association_distance = 0.5;  ///< m, element point association radius
  double gba_point_sigma = 0.05;          ///< m, point-to-line / point-to-plane sigma
  double gba_huber = 1.0;                 ///< Huber delta on whitened GBA residuals
  int gba_rounds = 2;                     ///< association / solve rounds
  int gba_max_partners = 2;               ///< other traversals tied to each point (0 = all)
  int gba_dof = 4;  ///< 6: full pose; 4: x, y, z, yaw (roll / pitch held where georef put them)
  int gba_line_stride = 2;  ///< GBA uses every n-th point of a line element, weighted sqrt(n)
  double gba_early_round_tolerance = 1e-2;  ///< LM stop of GBA rounds before the last
  int pcg_iterations = 50;                  ///< PCG iterations per LM step (pose graph and GBA)
  double pcg_tolerance = 1e-2;              ///< PCG stops at this relative residual
  double pcg_cell_size = 40.0;       ///< m, place cells of the PCG coarse level (0: chains only)
  int solver_iterations = 100;       ///< Levenberg-Marquardt iterations per solve
  double function_tolerance = 1e-2;  ///< LM stops when |cost change| / cost falls below
  int threads = 2;                   ///< OpenMP threads over pairs

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("method", method, "", "icp | sicp | sgicp | gba_sgicp", alignMethodNames());
    v("submap_length", submap_length, "m", "keyframe path length per submap", gt(0) & le(10000));
    v("min_overlap", min_overlap, "", "min share of coarse points near the other submap", in(0, 1));
    v("overlap_radius", overlap_radius, "m", "overlap test radius (GPS-level initial error)",
      gt(0) & le(100));
    v("max_partners", max_partners, "", "per submap, register with this many other LSMs (0 = all)",
      in(0, 100000));
    v("partner_choice", spread_partners, "",
      "overlap (the best-overlapping LSMs) | spread (an evenly spread subset of the overlapping "
      "LSMs)",
      Names<bool>{{{"overlap", false}, {"spread", true}}});
    v("coarse_radius", coarse_radius, "m", "coarse displacement-voting search radius",
      gt(0) & le(100));
    v("coarse_bin", coarse_bin, "m", "coarse displacement histogram bin", gt(0) & le(10));
    // the histogram holds (2 coarse_radius / coarse_bin)^2 cells
    v.relation("coarse_bin", coarse_bin, coarse_bin < coarse_radius, "< coarse_radius");
    v.relation("coarse_bin", coarse_bin, coarse_radius / coarse_bin <= 1000,
               ">= coarse_radius / 1000");
    v("coarse_prior_sigma", coarse_prior_sigma, "m", "Gaussian prior on the coarse shift",
      gt(0) & le(10000));
    v("coarse_neighbors", coarse_neighbors, "", "add votes of pairs of submaps this near",
      in(0, 100));
    v("coarse_class_weights", coarse_class_weights, "",
      "coarse vote weight per class (lane_line, stop_line, ground_arrow, crosswalk, "
      "traffic_sign, traffic_light, pole)",
      listOf(kNumCrowdClasses, kNumCrowdClasses, in(0, 1e6)));
    v("pyramid_distances", pyramid_distances, "m",
      "GICP max correspondence distance per pyramid level, coarse to fine",
      listOf(1, 8, gt(0) & le(100)));
    v("class_weights", class_weights, "",
      "GICP residual weight w_l per class (eq. 7; order as coarse_class_weights)",
      listOf(kNumCrowdClasses, kNumCrowdClasses, in(0, 1e6)));
    v("gicp_step_eps", gicp_step_eps, "m|rad", "a GICP level has converged at steps below this",
      gt(0) & le(1));
    v("gicp_lambda", gicp_lambda, "", "Levenberg damping of the GICP normal equations", in(0, 1e6));
    v("gicp_huber", gicp_huber, "sigma",
      "Huber delta on whitened GICP residuals (sicp / sgicp; 0: plain least squares)", in(0, 1e6));
    v("min_fitness", min_fitness, "", "accept registrations with inlier fraction above", in(0, 1));
    v("max_rmse", max_rmse, "m", "accept registrations with RMS residual below", gt(0) & le(100));
    v("min_information", min_information, "",
      "SGICP leaves directions with less information alone (0: off)", in(0, 1e12));
    v("max_iterations", max_iterations, "", "GICP iterations per pyramid level", in(1, 10000));
    v("pcm_gate", pcm_gate, "", "chi2 gate of PCM pairwise consistency (6 dof)", gt(0) & le(1e6));
    v("pcm_exact_max", pcm_exact_max, "", "exact maximum clique up to this many constraints",
      in(0, 200));
    v("odom_sigma_per_m", odom_sigma_per_m, "m/m", "relative odometry sigma per metre", in(0, 1));
    v("odom_min_sigma", odom_min_sigma, "m", "odometry sigma floor", gt(0) & le(100));
    v("prior_rotation_sigma", prior_rotation_sigma, "rad", "GPS prior sigma on attitude",
      gt(0) & le(10));
    v("gps_bias_sigma", gps_bias_sigma, "m",
      "horizontal GPS bias at the start of a traversal (0: independent priors per keyframe)",
      in(0, 1e4));
    v("gps_bias_vertical_sigma", gps_bias_vertical_sigma, "m",
      "vertical GPS bias at the start of a traversal", gt(0) & le(1e4));
    v("gps_bias_walk", gps_bias_walk, "m/sqrt(s)", "random walk of the GPS bias per axis",
      gt(0) & le(100));
    v("gps_bias_interval", gps_bias_interval, "s", "time between GPS bias nodes",
      gt(0) & le(1e6));
    v("inter_huber", inter_huber, "sigma", "Huber delta on inter-trajectory factors",
      gt(0) & le(1e6));
    v("constraint_min_sigma", constraint_min_sigma, "m", "floor of an InterRPC translation sigma",
      gt(0) & le(100));
    v("constraint_cov_scale", constraint_cov_scale, "", "inflation of the GICP inverse Hessian",
      gt(0) & le(1e6));
    v("graph_reject_chi2", graph_reject_chi2, "", "drop InterRPCs this far off the graph solution",
      gt(0) & le(1e12));
    v("graph_rejection_rounds", graph_rejection_rounds, "", "pose-graph solve / reject rounds",
      in(1, 100));
    v("gba_association_distance", gba_association_distance, "m", "GBA association radius",
      gt(0) & le(10));
    v("gba_point_sigma", gba_point_sigma, "m", "GBA point-to-line/plane sigma", gt(0) & le(10));
    v("gba_huber", gba_huber, "sigma", "Huber delta on GBA residuals", gt(0) & le(1e6));
    v("gba_rounds", gba_rounds, "", "GBA association / solve rounds", in(1, 100));
    v("gba_max_partners", gba_max_partners, "",
      "other traversals each element point is tied to (0 = all)", in(0, 100000));
    v("gba_dof", gba_dof, "",
      "GBA pose freedom: 4 (x, y, z, yaw; roll and pitch held from georef) or 6", in(4, 6));
    v.relation("gba_dof", gba_dof, gba_dof == 4 || gba_dof == 6, "is 4 or 6");
    v("gba_line_stride", gba_line_stride, "",
      "GBA uses every n-th point of a line element, weighted by sqrt(n)", in(1, 1000));
    v("pcg_iterations", pcg_iterations, "",
      "conjugate-gradient iterations per Levenberg-Marquardt step (pose graph and GBA)",
      in(1, 100000));
    v("pcg_tolerance", pcg_tolerance, "",
      "conjugate gradients stop at this residual relative to the right-hand side", gt(0) & lt(1));
    v("pcg_cell_size", pcg_cell_size, "m",
      "place cells of the conjugate-gradient coarse level (0: chains only)", in(0, 100000));
    v("gba_early_round_tolerance", gba_early_round_tolerance, "",
      "LM stop (relative cost change) of the GBA rounds before the last", gt(0) & lt(1));
    v("solver_iterations", solver_iterations, "", "Levenberg-Marquardt iterations per solve",
      in(1, 100000));
    v("function_tolerance", function_tolerance, "", "LM stop: relative cost change below",
      gt(0) & lt(1));
    v("threads", threads, "", "OpenMP threads over pairs / Ceres threads", in(1, 1024));
  }
};

/// An inter-trajectory relative pose constraint (InterRPC) between two keyframes.
struct InterConstraint {
  int lsm_a = 0, kf_a = 0;                     ///< target side (keyframe index)
  int lsm_b = 0, kf_b = 0;                     ///< source side
  Pose3 T_a_b = Pose3::Identity();             ///< measured body-a <- body-b
  Matrix6d covariance = Matrix6d::Identity();  ///< (rho, phi) of T_a_b
  double overlap = 0, fitness = 0, rmse = 0;
  int iterations = 0;
  bool converged = false;
  bool accepted = false;       ///< passed the registration checks
  bool consistent = false;     ///< kept by PCM
  bool graph_outlier = false;  ///< dropped after a pose-graph solve (chi2 > graph_reject_chi2)
  double graph_chi2 = 0;       ///< whitened squared residual at the last pose-graph solution
};

/// Registration labels of elementCloud: the crowd classes, plus dashed lane lines as their own
/// label so that a dashed divider never matches a solid centre or edge line one lane width away.
constexpr int kLabelDashedLine = kNumCrowdClasses;
constexpr int kNumAlignLabels = kNumCrowdClasses + 1;

/// @brief Per-label weights from per-class weights (dashed lines weigh like lane lines).
std::vector<double> labelWeights(const std::vector<double>& class_weights);

/// @brief Per-label weights of the coarse displacement vote: coarse_class_weights times the GICP
/// class_weights (w_l), per registration label.
std::vector<double> coarseVoteWeights(const AlignSettings& s);

/// @brief Element points of a keyframe range as a labelled cloud in the LSM frame, with
/// geometry-aware covariances (lines: free along the line; planar: free in the plane; poles:
/// free vertically), `point_sigma` across.
Cloud elementCloud(const Lsm& lsm, int kf_begin, int kf_end, double point_sigma = 0.05);

/// @brief Stage 1 registrations between overlapping submaps of different LSMs (OpenMP over pairs).
std::vector<InterConstraint> registerSubmaps(const std::vector<Lsm>& lsms, const AlignSettings& s);

/// @brief PCM: per pair of LSMs, the pairwise-consistency graph of its accepted constraints and
/// its maximum clique; sets `consistent`. @return number kept.
int pcmSelect(const std::vector<Lsm>& lsms, std::vector<InterConstraint>& constraints,
              const AlignSettings& s);

/// @brief Maximum clique of an undirected graph (adjacency matrix): exact branch and bound up to
/// `exact_max` vertices, greedy by degree above. Vertices returned sorted.
std::vector<int> maximumClique(const std::vector<std::vector<char>>& adjacency, int exact_max);

/// What a pose-graph or GBA solve did (summed over its rounds).
struct GraphSolve {
  double cost = 0;         ///< final cost of the last round (sum of rho(|r|^2) / 2)
  bool converged = false;  ///< the last round met the function tolerance
  int rounds = 0;          ///< pose-graph rejection rounds / GBA association rounds
  int iterations = 0;      ///< Levenberg-Marquardt iterations
  int pcg_iterations = 0;  ///< conjugate-gradient iterations of the linear solves
  int residuals = 0;       ///< GBA: element residuals of the last round
  int blocks = 0;          ///< off-diagonal blocks of the normal equations, last round
  int keyframes = 0;       ///< poses solved for
};

/// @brief Multi-trajectory pose graph, eq. (8)-(11): GPS priors from the georeferenced keyframes
/// (`priors[l].keyframes`; their elements are not used), odometry between consecutive
/// keyframes, Huber-robust InterRPCs (only `consistent` ones). Updates keyframe poses in place.
/// Constraints whose residual at the solution exceeds `graph_reject_chi2` are marked
/// `graph_outlier` and the graph is solved again (up to `graph_rejection_rounds` solves).
/// Levenberg-Marquardt with PCG steps: O(keyframes + constraints) per iteration.
GraphSolve solveMultiPoseGraph(std::vector<Lsm>& lsms, const std::vector<Lsm>& priors,
                               std::vector<InterConstraint>& constraints, const AlignSettings& s);

/// @brief GBA, eq. (12)-(14): point-to-line (lane/stop lines, poles) and point-to-plane (arrows,
/// crosswalks, signs) residuals between elements of different LSMs, Huber loss, GPS priors and
/// odometry from `priors[l].keyframes` (georef output). Each point is tied to at most
/// `gba_max_partners` other traversals, chosen per keyframe. Updates keyframe poses in place.
GraphSolve solveGba(std::vector<Lsm>& lsms, const std::vector<Lsm>& priors, const AlignSettings& s);

/// How far the crowd ties each stretch of road (issue 36): per stretch of `stretch_m` of each
/// traversal's keyframe path, the other traversals its kept registrations (accepted, PCM
/// consistent, not graph outliers) reach directly. A stretch tied to none keeps its own GPS
/// bias in the map; one tied to many shares their mean (src/fusion/gps_bias.hpp).
struct TieStatistics {
  double stretch_m = 0;
  std::vector<int> tied;  ///< per stretch, traversal after traversal, in path order
  int median() const;         ///< tied traversals of the median stretch (0 without stretches)
  double untiedShare() const; ///< share of stretches tied to none
};

/// @brief Ties per `stretch_m` of path. O(keyframes + constraints).
TieStatistics tieStatistics(const std::vector<Lsm>& lsms,
                            const std::vector<InterConstraint>& constraints, double stretch_m);

/// What align did: every registration with its checks, the solves' costs and timings.
struct AlignResult {
  AlignMethod method = AlignMethod::kGbaSgicp;
  std::vector<InterConstraint> constraints;  ///< proposed registrations, with their outcome
  int constraints_accepted = 0;              ///< passed the registration checks
  int constraints_pcm_kept = 0;              ///< kept by PCM
  int constraints_graph_outliers = 0;        ///< dropped by the pose graph
  GraphSolve pose_graph;                     ///< eq. (8)-(11); rounds = solve / reject rounds
  bool ran_gba = false;                      ///< method gba_sgicp
  GraphSolve gba;                            ///< eq. (12)-(14), when ran_gba
  bool converged = false;                    ///< the last solve converged
  double seconds_registration = 0, seconds_pcm = 0, seconds_pose_graph = 0, seconds_gba = 0;
  TieStatistics ties;  ///< per kTieStretch m of path (tieStatistics)
};

/// m, the stretch of alignLsms' tie statistics: about eight submaps (submap_length 60 m).
constexpr double kTieStretch = 500.0;

/// @brief The whole of §4.2: registrations (eq. 7), PCM, the multi-trajectory pose graph
/// (eq. 8-11) and, for gba_sgicp, GBA (eq. 12-14). Moves the keyframes of `lsms` in place.
AlignResult alignLsms(std::vector<Lsm>& lsms, const AlignSettings& s);

}  // namespace mapfuse::fusion
