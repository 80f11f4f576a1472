#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "mapfuse/core/error.hpp"
#include "mapfuse/tiling/placement.hpp"

using namespace mapfuse;
using namespace mapfuse::tiling;

namespace {
constexpr double kPlacementTol = 0.05;  // m: balanced tile vs the batch-wide mean georef error
constexpr double kAlignNoise = 0.03;    // m: per-piece noise of a tile's align shift
constexpr double kPieceSeconds = 20.0;  // s: time a drive spends in one tile
constexpr double kDriftGain = 0.3;      // worst tile offset after / before, drifting errors

// Drives along a row of tiles, each with a GPS-like georef error (1-3 m, random direction,
// random walk in time) and a contiguous run of tiles; in every tile the drives fall into
// `groups` registration groups (say, roads that do not meet inside the tile). Align puts each
// group at the mean georef error of its own pieces, o_g; piece shift s_p = o_g - e_p + noise.
struct RowWorld {
  std::vector<TilePiece> pieces;
  std::vector<Eigen::Vector3d> errors;    // e_p per piece
  std::map<GroupKey, Eigen::Vector3d> o;  // per group, as independent align leaves it
  Eigen::Vector3d batch_mean = Eigen::Vector3d::Zero();
};

RowWorld rowWorld(int tiles, int drives, unsigned seed, double walk = 0.05, int groups = 1) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  std::normal_distribution<double> N01(0.0, 1.0);
  RowWorld w;
  for (int d = 0; d < drives; ++d) {
    const int a = int(U(rng) * tiles), b = std::min(tiles - 1, a + int(U(rng) * tiles));
    const double mag = 1.0 + 2.0 * U(rng), dir = 2.0 * M_PI * U(rng);
    Eigen::Vector3d e(mag * std::cos(dir), mag * std::sin(dir), 0.5 * N01(rng));
    for (int t = a; t <= b; ++t) {
      if (t > a)
        e.head<2>() += walk * std::sqrt(kPieceSeconds) * Eigen::Vector2d(N01(rng), N01(rng));
      TilePiece p;
      p.group = GroupKey{TileKey{t, 0}, d % groups};
      p.drive = "drive" + std::to_string(d);
      p.stamp = 1000.0 * d + kPieceSeconds * t;
      p.keyframes = 20;
      w.pieces.push_back(p);
      w.errors.push_back(e);
    }
  }
  std::map<GroupKey, int> count;
  for (std::size_t i = 0; i < w.pieces.size(); ++i) {
    w.o.emplace(w.pieces[i].group, Eigen::Vector3d::Zero()).first->second += w.errors[i];
    ++count[w.pieces[i].group];
    w.batch_mean += w.errors[i];
  }
  for (auto& [key, sum] : w.o) sum /= count[key];
  w.batch_mean /= double(w.pieces.size());
  for (std::size_t i = 0; i < w.pieces.size(); ++i)
    w.pieces[i].shift = w.o[w.pieces[i].group] - w.errors[i] +
                        kAlignNoise * Eigen::Vector3d(N01(rng), N01(rng), N01(rng));
  return w;
}

double worstOffset(const RowWorld& w, const std::map<GroupKey, Eigen::Vector3d>& shifts) {
  double worst = 0.0;
  for (const auto& [key, o] : w.o) {
    const Eigen::Vector3d s = shifts.count(key) ? shifts.at(key) : Eigen::Vector3d::Zero();
    worst = std::max(worst, (o + s - w.batch_mean).head<2>().norm());
  }
  return worst;
}
}  // namespace

TEST_CASE("tiles are placed at the batch-wide mean georef error", "[tiling][placement]") {
  for (unsigned seed : {1u, 2u, 4u}) {
    const RowWorld w = rowWorld(6, 40, seed, 0.0);
    // Independent tiles each sit at their own drives' mean: a real offset between them.
    INFO("seed " << seed << ": independent tiles up to " << worstOffset(w, {}) << " m off");
    REQUIRE(worstOffset(w, {}) > 3 * kPlacementTol);
    PlacementReport report;
    const auto shifts = solvePlacement(w.pieces, PlacementParams{}, report);
    CHECK(shifts.size() == 6);
    CHECK(report.tiles == 6);
    CHECK(report.drives == 40);
    CHECK(report.pieces == int(w.pieces.size()));
    CHECK(worstOffset(w, shifts) < kPlacementTol);
  }
}

TEST_CASE("drifting georef errors: groups come closer to the batch mean", "[tiling][placement]") {
  // A drive's error drifts 0.22 m (1 sigma) from one tile to the next, so a tile's offset is
  // known only as well as the drifts of the drives through it average out.
  double raw = 0.0, placed = 0.0;
  for (unsigned seed = 1; seed <= 10; ++seed) {
    const RowWorld w = rowWorld(6, 40, seed);
    PlacementReport report;
    const auto shifts = solvePlacement(w.pieces, PlacementParams{}, report);
    CHECK(worstOffset(w, shifts) < worstOffset(w, {}));
    raw += worstOffset(w, {});
    placed += worstOffset(w, shifts);
  }
  CHECK(placed < kDriftGain * raw);
}

TEST_CASE("one group alone keeps its place", "[tiling][placement]") {
  const RowWorld w = rowWorld(1, 10, 4);
  PlacementReport report;
  const auto shifts = solvePlacement(w.pieces, PlacementParams{}, report);
  REQUIRE(shifts.size() == 1);
  CHECK(shifts.begin()->second.head<2>().norm() < kPlacementTol);
}

TEST_CASE("a piece whose alignment went wrong does not move its group", "[tiling][placement]") {
  RowWorld w = rowWorld(5, 30, 5, 0.0);
  PlacementReport clean_report;
  const auto clean = solvePlacement(w.pieces, PlacementParams{}, clean_report);
  // A drive over tiles 1-3 with a 2.5 m georef error that tile 2's align left where it was.
  for (int t = 1; t <= 3; ++t) {
    TilePiece p;
    p.group = GroupKey{TileKey{t, 0}, 0};
    p.drive = "refused";
    p.stamp = 1e6 + kPieceSeconds * t;
    p.keyframes = 20;
    p.shift = w.o[p.group] - Eigen::Vector3d(2.5, 0.0, 0.0);
    if (t == 2) p.shift.setZero();
    w.pieces.push_back(p);
  }
  PlacementReport report;
  const auto robust = solvePlacement(w.pieces, PlacementParams{}, report);
  CHECK(report.downweighted >= 1);
  // The new drive moves the batch mean (and so every tile alike); tile 2 keeps its place
  // relative to its neighbours.
  const auto relative = [](const auto& shifts) {
    return Eigen::Vector3d(shifts.at(GroupKey{TileKey{2, 0}, 0}) -
                           shifts.at(GroupKey{TileKey{1, 0}, 0}));
  };
  CHECK((relative(robust) - relative(clean)).head<2>().norm() < kPlacementTol);
  PlacementParams plain;
  plain.rounds = 1;  // plain least squares: the refused piece drags its tile
  const auto dragged = solvePlacement(w.pieces, plain, report);
  CHECK((relative(dragged) - relative(clean)).head<2>().norm() > kPlacementTol);
}

TEST_CASE("placement pieces: drive of a split run, shift by keyframe id", "[tiling][placement]") {
  CHECK(driveOfPiece("0007.run2") == "0007");
  CHECK(driveOfPiece("0007") == "0007");
  CHECK(driveOfPiece("a.run.x") == "a.run.x");

  Lsm georef, aligned;
  georef.drive_id = aligned.drive_id = "d.run1";
  for (int i = 0; i < 4; ++i) {
    Keyframe k;
    k.id = 10 + i;
    k.stamp = i;
    k.T_frame_body.translation() = Eigen::Vector3d(10.0 * i, 0, 0);
    georef.keyframes.push_back(k);
    if (i == 0) continue;  // align's output may hold fewer keyframes: matched by id
    k.T_frame_body.translation() += Eigen::Vector3d(0.3, -0.6, 0.1);
    aligned.keyframes.push_back(k);
  }
  const TilePiece p = measurePiece(georef, aligned);
  CHECK(p.drive == "d");
  CHECK(p.keyframes == 3);
  CHECK(p.stamp == Approx(2.0));
  CHECK((p.shift - Eigen::Vector3d(0.3, -0.6, 0.1)).norm() < 1e-12);

  aligned.drive_id = "other";
  CHECK_THROWS_AS(measurePiece(georef, aligned), InputError);
  aligned.drive_id = georef.drive_id;
  for (auto& k : aligned.keyframes) k.id += 100;
  CHECK_THROWS_AS(measurePiece(georef, aligned), InputError);
}

TEST_CASE("registration groups are the connected components of the kept links", "[tiling]") {
  CHECK(registrationGroups(5, {{3, 1}, {4, 3}}) == std::vector<int>{0, 1, 2, 1, 1});
  CHECK(registrationGroups(3, {}) == std::vector<int>{0, 1, 2});
  CHECK(registrationGroups(0, {}).empty());
  CHECK_THROWS_AS(registrationGroups(2, {{0, 2}}), InputError);
}

TEST_CASE("placement parameters are validated with their field names", "[tiling][config]") {
  PlacementParams p;
  CHECK_NOTHROW(p.validate());
  p.piece_sigma = 0.0;
  CHECK_THROWS_WITH(p.validate(), Catch::Contains("BalanceParams::piece_sigma"));
  p = PlacementParams{};
  p.rounds = 0;
  CHECK_THROWS_AS(p.validate(), ConfigError);
  p = PlacementParams{};
  p.robust_scale = -1.0;
  CHECK_THROWS_AS(p.validate(), ConfigError);
}
