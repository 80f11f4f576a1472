#include "mapfuse/tiling/placement.hpp"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <regex>
#include <set>
#include <unordered_map>

#include "mapfuse/core/error.hpp"
#include "mapfuse/core/params.hpp"

namespace mapfuse::tiling {

void PlacementParams::validate() const {
  requireParam(piece_sigma > 0.0, "BalanceParams", "piece_sigma", piece_sigma, "> 0");
  requireParam(bias_walk >= 0.0, "BalanceParams", "bias_walk", bias_walk, ">= 0");
  requireParam(robust_scale > 0.0, "BalanceParams", "robust_scale", robust_scale, "> 0");
  requireParam(rounds >= 1, "BalanceParams", "rounds", rounds, ">= 1");
}

std::string driveOfPiece(const std::string& drive_id) {
  static const std::regex kRun("(.*)\\.run[0-9]+");
  std::smatch m;
  return std::regex_match(drive_id, m, kRun) ? m[1].str() : drive_id;
}

TilePiece measurePiece(const Lsm& georef, const Lsm& aligned) {
  if (georef.drive_id != aligned.drive_id)
    throw InputError("aligned LSM " + aligned.drive_id + " does not match its input " +
                     georef.drive_id);
  std::unordered_map<int64_t, const Keyframe*> before;
  for (const auto& k : georef.keyframes) before[k.id] = &k;
  TilePiece p;
  p.drive = driveOfPiece(georef.drive_id);
  for (const auto& k : aligned.keyframes) {
    const auto it = before.find(k.id);
    if (it == before.end()) continue;
    p.shift += k.T_frame_body.translation() - it->second->T_frame_body.translation();
    p.stamp += k.stamp;
    ++p.keyframes;
  }
  if (p.keyframes == 0)
    throw InputError("aligned LSM " + aligned.drive_id + " shares no keyframe id with its input");
  p.shift /= p.keyframes;
  p.stamp /= p.keyframes;
  return p;
}

std::vector<int> registrationGroups(int n, const std::vector<std::pair<int, int>>& links) {
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (const auto& [a, b] : links) {
    if (a < 0 || b < 0 || a >= n || b >= n)
      throw InputError("registration link " + std::to_string(a) + "-" + std::to_string(b) +
                       " outside 0.." + std::to_string(n - 1));
    parent[root(a)] = root(b);
  }
  std::vector<int> group(n);
  std::unordered_map<int, int> number;
  for (int i = 0; i < n; ++i) group[i] = number.emplace(root(i), int(number.size())).first->second;
  return group;
}

namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;

// Adds w * (x_i - x_j)^2 to the normal matrix.
void addDifference(Triplets& A, int i, int j, double w) {
  A.emplace_back(i, i, w);
  A.emplace_back(j, j, w);
  A.emplace_back(i, j, -w);
  A.emplace_back(j, i, -w);
}

}  // namespace

std::map<GroupKey, Eigen::Vector3d> solvePlacement(const std::vector<TilePiece>& pieces,
                                                   const PlacementParams& params,
                                                   PlacementReport& report) {
  params.validate();
  report = PlacementReport{};
  // Unknowns: o_g for every group (0..G-1), then e_p for every piece (G..G+P-1).
  std::map<GroupKey, int> group_index;
  std::set<TileKey> tiles;
  for (const auto& p : pieces) {
    group_index.emplace(p.group, 0);
    tiles.insert(p.group.tile);
  }
  int next = 0;
  for (auto& [key, index] : group_index) index = next++;
  const int G = int(group_index.size()), P = int(pieces.size()), N = G + P;
  report.tiles = int(tiles.size());
  report.groups = G;
  report.pieces = P;
  if (P == 0) return {};

  // A drive's consecutive pieces (in time) share its georef error up to a random walk.
  std::map<std::string, std::vector<int>> by_drive;
  for (int p = 0; p < P; ++p) by_drive[pieces[p].drive].push_back(p);
  report.drives = int(by_drive.size());
  Triplets walk;
  for (auto& [drive, list] : by_drive) {
    std::sort(list.begin(), list.end(),
              [&](int a, int b) { return pieces[a].stamp < pieces[b].stamp; });
    for (std::size_t i = 1; i < list.size(); ++i) {
      const double dt = std::abs(pieces[list[i]].stamp - pieces[list[i - 1]].stamp);
      const double var = params.bias_walk * params.bias_walk * dt + 1e-4;
      addDifference(walk, G + list[i - 1], G + list[i], 1.0 / var);
    }
  }

  const double w_obs = 1.0 / (params.piece_sigma * params.piece_sigma);
  // Gauge: georef errors are zero-mean over the batch. A vanishing prior on every e_p, weighted
  // by its keyframes, fixes the one common shift that the observations leave free.
  const double w_gauge = 1e-6 * w_obs;
  std::vector<double> robust(P, 1.0);
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(N, 3);
  for (int round = 0; round < params.rounds; ++round) {
    Triplets A = walk;
    Eigen::MatrixXd b = Eigen::MatrixXd::Zero(N, 3);
    for (int p = 0; p < P; ++p) {
      const int g = group_index.at(pieces[p].group), e = G + p;
      const double w = w_obs * robust[p];
      addDifference(A, g, e, w);  // residual o_g - e_p - s_p
      b.row(g) += w * pieces[p].shift.transpose();
      b.row(e) -= w * pieces[p].shift.transpose();
      A.emplace_back(e, e, w_gauge * pieces[p].keyframes);
    }
    Eigen::SparseMatrix<double> M(N, N);
    M.setFromTriplets(A.begin(), A.end());
    const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(M);
    if (ldlt.info() != Eigen::Success) throw Error("balance: the placement system is singular");
    x = ldlt.solve(b);

    double sum_sq = 0.0;
    report.downweighted = 0;
    for (int p = 0; p < P; ++p) {
      const int g = group_index.at(pieces[p].group);
      const Eigen::Vector3d r = x.row(g).transpose() - x.row(G + p).transpose() - pieces[p].shift;
      const double u = r.head<2>().norm() / params.robust_scale;
      sum_sq += r.head<2>().squaredNorm();
      robust[p] = 1.0 / (1.0 + u * u);
      if (u > 1.0) ++report.downweighted;
    }
    report.rms_residual = std::sqrt(sum_sq / P);
  }

  std::map<GroupKey, Eigen::Vector3d> shifts;
  for (const auto& [key, g] : group_index) {
    shifts[key] = -x.row(g).transpose();
    report.max_shift = std::max(report.max_shift, shifts[key].head<2>().norm());
  }
  return shifts;
}

}  // namespace mapfuse::tiling
