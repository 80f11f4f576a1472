#include "mapfuse/tiling/placement.hpp"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <regex>
#include <set>
#include <unordered_map>

#include "mapfuse/core/error.hpp"
#include "mapfuse/core/union_find.hpp"

namespace mapfuse::tiling {

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
    p.keyframes.push_back(
        {k.id, k.stamp, k.T_frame_body.translation() - it->second->T_frame_body.translation()});
  }
  if (p.keyframes.empty())
    throw InputError("aligned LSM " + aligned.drive_id + " shares no keyframe id with its input");
  return p;
}

std::vector<int> registrationGroups(int n, const std::vector<std::pair<int, int>>& links) {
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  for (const auto& [a, b] : links) {
    if (a < 0 || b < 0 || a >= n || b >= n)
      throw InputError("registration link " + std::to_string(a) + "-" + std::to_string(b) +
                       " outside 0.." + std::to_string(n - 1));
    parent[findRoot(parent, a)] = findRoot(parent, b);
  }
  std::vector<int> group(n);
  std::unordered_map<int, int> number;
  for (int i = 0; i < n; ++i)
    group[i] = number.emplace(findRoot(parent, i), int(number.size())).first->second;
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
  report = PlacementReport{};
  // Unknowns: o_g for every group (0..G-1), then e_k for every distinct drive keyframe.
  std::map<GroupKey, int> group_index;
  std::set<TileKey> tiles;
  for (const auto& p : pieces) {
    group_index.emplace(p.group, 0);
    tiles.insert(p.group.tile);
  }
  int next = 0;
  for (auto& [key, index] : group_index) index = next++;
  const int G = next;
  std::map<std::pair<std::string, int64_t>, int> kf_index;  // (drive, keyframe id) -> unknown
  std::map<std::string, std::map<double, int>> by_drive;    // drive -> stamp -> unknown
  std::vector<std::vector<int>> unknown_of(pieces.size());  // per piece and keyframe
  for (std::size_t p = 0; p < pieces.size(); ++p)
    for (const auto& k : pieces[p].keyframes) {
      const auto [it, added] = kf_index.emplace(std::make_pair(pieces[p].drive, k.id), 0);
      if (added) {
        it->second = G + int(kf_index.size()) - 1;
        by_drive[pieces[p].drive].emplace(k.stamp, it->second);
      }
      unknown_of[p].push_back(it->second);
    }
  const int N = G + int(kf_index.size());
  report.tiles = int(tiles.size());
  report.groups = G;
  report.pieces = int(pieces.size());
  report.drives = int(by_drive.size());
  report.keyframes = int(kf_index.size());
  if (pieces.empty()) return {};

  // A drive's consecutive keyframes share its georef error up to a random walk.
  Triplets walk;
  for (const auto& [drive, stamps] : by_drive) {
    auto prev = stamps.end();
    for (auto it = stamps.begin(); it != stamps.end(); prev = it++) {
      if (prev == stamps.end()) continue;
      const double var = params.bias_walk * params.bias_walk * (it->first - prev->first) + 1e-4;
      addDifference(walk, prev->second, it->second, 1.0 / var);
    }
  }

  const double w_obs = 1.0 / (params.keyframe_sigma * params.keyframe_sigma);
  // Gauge: georef errors are zero-mean over the batch. A vanishing prior on every e_k fixes the
  // one common shift that the observations leave free.
  const double w_gauge = 1e-6 * w_obs;
  std::vector<double> robust(pieces.size(), 1.0);
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(N, 3);
  for (int round = 0; round < params.rounds; ++round) {
    Triplets A = walk;
    for (int i = G; i < N; ++i) A.emplace_back(i, i, w_gauge);
    Eigen::MatrixXd b = Eigen::MatrixXd::Zero(N, 3);
    for (std::size_t p = 0; p < pieces.size(); ++p) {
      const int g = group_index.at(pieces[p].group);
      const double w = w_obs * robust[p];
      for (std::size_t j = 0; j < pieces[p].keyframes.size(); ++j) {
        const int e = unknown_of[p][j];
        const Eigen::RowVector3d s = pieces[p].keyframes[j].shift.transpose();
        addDifference(A, g, e, w);  // residual o_g - e_k - s_tk
        b.row(g) += w * s;
        b.row(e) -= w * s;
      }
    }
    Eigen::SparseMatrix<double> M(N, N);
    M.setFromTriplets(A.begin(), A.end());
    const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(M);
    if (ldlt.info() != Eigen::Success) throw Error("balance: the placement system is singular");
    x = ldlt.solve(b);

    // Reweight each piece by its mean residual: a piece aligned wrongly is off as a whole.
    double sum_sq = 0.0;
    int count = 0;
    report.downweighted = 0;
    for (std::size_t p = 0; p < pieces.size(); ++p) {
      const int g = group_index.at(pieces[p].group);
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      for (std::size_t j = 0; j < pieces[p].keyframes.size(); ++j) {
        const Eigen::Vector3d r = x.row(g).transpose() - x.row(unknown_of[p][j]).transpose() -
                                  pieces[p].keyframes[j].shift;
        mean += r;
        sum_sq += r.head<2>().squaredNorm();
        ++count;
      }
      mean /= double(pieces[p].keyframes.size());
      const double u = mean.head<2>().norm() / params.robust_scale;
      robust[p] = 1.0 / (1.0 + u * u);
      if (u > 1.0) ++report.downweighted;
    }
    report.rms_residual = std::sqrt(sum_sq / count);
  }

  std::map<GroupKey, Eigen::Vector3d> shifts;
  for (const auto& [key, g] : group_index) {
    shifts[key] = -x.row(g).transpose();
    report.max_shift = std::max(report.max_shift, shifts[key].head<2>().norm());
  }
  return shifts;
}

}  // namespace mapfuse::tiling
