#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <random>

#include "mapfuse/cli/params.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/tiling/piece_links.hpp"
#include "mapfuse/tiling/placement.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;
using namespace mapfuse::tiling;

namespace {
constexpr double kPlacementTol = 0.05;  // m: balanced group vs the batch-wide mean georef error
constexpr double kAlignNoise = 0.03;    // m: per-keyframe noise of a tile's align shift
constexpr int kPieceKeyframes = 20;     // keyframes (1 s apart) a drive has in one tile's core
constexpr int kMargin = 3;              // keyframes a piece reaches into each neighbour tile
constexpr double kDriftGain = 0.3;      // worst group offset after / before, drifting errors

// Drives along a row of tiles, each with a GPS-like georef error (1-3 m, random direction,
// random walk in time, per keyframe) over a contiguous run of tiles; a piece holds the drive's
// keyframes in its tile's core plus kMargin on each side (shared with the neighbour's piece).
// In every tile the drives fall into the registration groups `group_of` says (roads that do not
// meet inside the tile). Align puts each group at the mean georef error of its keyframes, o_g, and
// shifts keyframe k by s = o_g - e_k + noise.
struct RowWorld {
  std::vector<TilePiece> pieces;
  std::vector<std::vector<Eigen::Vector3d>> errors;  // e_k per piece and keyframe
  std::map<GroupKey, Eigen::Vector3d> o;             // per group, as independent align leaves it
  Eigen::Vector3d batch_mean = Eigen::Vector3d::Zero();  // over distinct drive keyframes
};

using GroupOf = std::function<int(int drive, int tile)>;

RowWorld rowWorld(
    int tiles, int drives, unsigned seed, double walk = 0.05,
    const GroupOf& group_of = [](int, int) { return 0; }) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  std::normal_distribution<double> N01(0.0, 1.0);
  RowWorld w;
  int distinct = 0;
  for (int d = 0; d < drives; ++d) {
    const int a = int(U(rng) * tiles), b = std::min(tiles - 1, a + int(U(rng) * tiles));
    const double mag = 1.0 + 2.0 * U(rng), dir = 2.0 * M_PI * U(rng);
    Eigen::Vector3d e(mag * std::cos(dir), mag * std::sin(dir), 0.5 * N01(rng));
    const int n = (b - a + 1) * kPieceKeyframes;
    std::vector<Eigen::Vector3d> drive_e;
    for (int k = 0; k < n; ++k) {
      if (k > 0)
        e.head<2>() += walk * mapfuse::test::drawVector<Eigen::Vector2d>(N01, rng);  // 1 s steps
      drive_e.push_back(e);
      w.batch_mean += e;
      ++distinct;
    }
    for (int t = a; t <= b; ++t) {
      TilePiece p;
      p.group = GroupKey{TileKey{t, 0}, group_of(d, t)};
      p.drive = "drive" + std::to_string(d);
      std::vector<Eigen::Vector3d> pe;
      const int k0 = std::max(0, (t - a) * kPieceKeyframes - kMargin);
      const int k1 = std::min(n, (t - a + 1) * kPieceKeyframes + kMargin);
      for (int k = k0; k < k1; ++k) {
        p.keyframes.push_back({k, 1000.0 * d + k, Eigen::Vector3d::Zero()});
        pe.push_back(drive_e[k]);
      }
      w.pieces.push_back(p);
      w.errors.push_back(pe);
    }
  }
  w.batch_mean /= double(distinct);
  std::map<GroupKey, int> count;
  for (std::size_t i = 0; i < w.pieces.size(); ++i)
    for (const auto& e : w.errors[i]) {
      w.o.emplace(w.pieces[i].group, Eigen::Vector3d::Zero()).first->second += e;
      ++count[w.pieces[i].group];
    }
  for (auto& [key, sum] : w.o) sum /= count[key];
  for (std::size_t i = 0; i < w.pieces.size(); ++i)
    for (std::size_t k = 0; k < w.errors[i].size(); ++k)
      w.pieces[i].keyframes[k].shift =
          w.o[w.pieces[i].group] - w.errors[i][k] +
          kAlignNoise * mapfuse::test::drawVector<Eigen::Vector3d>(N01, rng);
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

TEST_CASE("groups are placed at the batch-wide mean georef error", "[tiling][placement]") {
  // Even drives and odd drives take different roads through odd tiles and meet in even ones.
  const GroupOf junctions = [](int d, int t) { return t % 2 == 0 ? 0 : d % 2; };
  for (unsigned seed : {1u, 2u, 4u}) {
    const RowWorld w = rowWorld(6, 40, seed, 0.0, junctions);
    // Independent groups each sit at their own drives' mean: a real offset between them.
    INFO("seed " << seed << ": independent groups up to " << worstOffset(w, {}) << " m off");
    REQUIRE(worstOffset(w, {}) > 3 * kPlacementTol);
    PlacementReport report;
    const auto shifts = solvePlacement(w.pieces, PlacementParams{}, report);
    CHECK(shifts.size() == w.o.size());
    CHECK(report.tiles == 6);
    CHECK(report.groups == int(w.o.size()));
    CHECK(report.drives == 40);
    CHECK(report.pieces == int(w.pieces.size()));
    CHECK(worstOffset(w, shifts) < kPlacementTol);
  }
}

TEST_CASE("drives that never meet are placed by their own GPS", "[tiling][placement]") {
  // Even and odd drives never share a group: nothing ties the two sets, so each is placed at
  // the mean georef error of its own drives, as an untiled run would place them.
  const RowWorld w = rowWorld(6, 40, 1, 0.0, [](int d, int) { return d % 2; });
  PlacementReport report;
  const auto shifts = solvePlacement(w.pieces, PlacementParams{}, report);
  for (int parity = 0; parity < 2; ++parity) {
    std::map<std::pair<std::string, int64_t>, Eigen::Vector3d> distinct;  // each keyframe once
    for (std::size_t i = 0; i < w.pieces.size(); ++i)
      if (w.pieces[i].group.group == parity)
        for (std::size_t k = 0; k < w.errors[i].size(); ++k)
          distinct[{w.pieces[i].drive, w.pieces[i].keyframes[k].id}] = w.errors[i][k];
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto& [key, e] : distinct) mean += e / double(distinct.size());
    for (const auto& [key, o] : w.o)
      if (key.group == parity) CHECK((o + shifts.at(key) - mean).head<2>().norm() < kPlacementTol);
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

TEST_CASE("a piece align could not register follows its drive", "[tiling][placement]") {
  RowWorld w = rowWorld(5, 30, 5, 0.0);
  // A drive over tiles 1-3 with a 2.5 m georef error: registered in tiles 1 and 3, left where
  // GPS put it in tile 2, where it is a group of its own (balance links nothing to it).
  const Eigen::Vector3d e(2.5, 0.0, 0.0);
  for (int t = 1; t <= 3; ++t) {
    TilePiece p;
    p.group = GroupKey{TileKey{t, 0}, t == 2 ? 1 : 0};
    p.drive = "refused";
    for (int k = 0; k < kPieceKeyframes; ++k) {
      const int id = (t - 1) * kPieceKeyframes + k;
      const Eigen::Vector3d s =
          t == 2 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(w.o[p.group] - e);
      p.keyframes.push_back({id, 1e6 + id, s});
    }
    w.pieces.push_back(p);
  }
  PlacementReport report;
  const auto shifts = solvePlacement(w.pieces, PlacementParams{}, report);
  // Placed, the lone piece sits where its drive sits in tiles 1 and 3 (true + the same common
  // offset as everything else): its shift is (o_1 + shift_1) - e relative to georef.
  const GroupKey one{TileKey{1, 0}, 0}, lone{TileKey{2, 0}, 1};
  const Eigen::Vector3d placed_drive = w.o[one] + shifts.at(one) - e;  // aligned + shift - georef
  CHECK((shifts.at(lone) - placed_drive).head<2>().norm() < kPlacementTol);
  CHECK(shifts.at(lone).head<2>().norm() > 2.0);  // it moved by about its georef error
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
  REQUIRE(p.keyframes.size() == 3);
  CHECK(p.keyframes[0].id == 11);
  CHECK(p.keyframes[2].stamp == Approx(3.0));
  for (const auto& k : p.keyframes)
    CHECK((k.shift - Eigen::Vector3d(0.3, -0.6, 0.1)).norm() < 1e-12);

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
  CHECK_NOTHROW(validateParams(p, "BalanceParams"));
  p.keyframe_sigma = 0.0;
  CHECK_THROWS_WITH(validateParams(p, "BalanceParams"),
                    Catch::Contains("BalanceParams::keyframe_sigma"));
  p = PlacementParams{};
  p.rounds = 0;
  CHECK_THROWS_AS(validateParams(p, "BalanceParams"), ConfigError);
  p = PlacementParams{};
  p.robust_scale = -1.0;
  CHECK_THROWS_AS(validateParams(p, "BalanceParams"), ConfigError);
}

TEST_CASE("pieces whose elements coincide after alignment are linked", "[tiling][placement]") {
  // Lane points every 0.75 m along y = 1.75 in three pieces: b on a within 0.1 m, c 1 m aside;
  // d holds the same points as a but as poles (another class).
  auto piece = [](double dy, CrowdClass cls) {
    Lsm lsm;
    lsm.frame = LsmFrame::kEnu;
    Keyframe k;
    k.id = 7;
    lsm.keyframes.push_back(k);
    Element e;
    e.anchor = 7;
    e.cls = cls;
    for (int i = 0; i < 40; ++i) e.points_body.emplace_back(0.75 * i, 1.75 + dy, 0.0);
    e.covariances.assign(e.points_body.size(), Eigen::Matrix3d::Identity() * 0.01);
    lsm.elements.push_back(e);
    return lsm;
  };
  const std::vector<Lsm> lsms = {piece(0.0, CrowdClass::kLaneLine),
                                 piece(0.1, CrowdClass::kLaneLine),
                                 piece(1.0, CrowdClass::kLaneLine), piece(0.0, CrowdClass::kPole)};
  CHECK(agreeingPieces(lsms, 0.3, 10) == std::vector<std::pair<int, int>>{{0, 1}});
  CHECK(agreeingPieces(lsms, 0.3, 41).empty());      // 40 coinciding points are not enough
  CHECK(agreeingPieces(lsms, 1.2, 10).size() == 3);  // c joins a and b at 1.2 m
}
