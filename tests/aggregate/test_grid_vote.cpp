// The grid-vote baseline (Qin et al. 2021; aggregate --method grid_vote): the votes of a cell,
// its majority class, and the lines and markings it recovers from the hand-built road of
// synthetic_world.hpp.
#include <catch2/catch.hpp>
#include <cmath>

#include "aggregate/grid_vote.hpp"
#include "mapfuse/aggregate/aggregator.hpp"
#include "mapfuse/aggregate/geometry2d.hpp"
#include "mapfuse/core/error.hpp"
#include "synthetic_world.hpp"

using namespace mapfuse;
using namespace mapfuse::aggregate;
using Vec3 = Eigen::Vector3d;

namespace {

// Lane points: 10 drives offset by N(0, 5 cm) each, voted on 10 cm cells (the centre of a cell
// is up to 7 cm from any point in it), then binned and Bezier-fitted (8 cm); at a line's ends the
// strokes reach half a line width plus half a cell beyond it.
constexpr double kLanePointTolerance = 0.20;  // m, every map lane point to its truth line
constexpr double kLanePointTypical = 0.10;    // m, ...and nearly all of them
constexpr double kTypicalShare = 0.97;
constexpr double kMinCoverage = 0.95;        // of the truth lines' length
constexpr double kDiscreteTolerance = 0.15;  // m, instance centre to truth centre

AggregatorParams gridVote() {
  AggregatorParams p;
  p.method = "grid_vote";
  return p;
}

using test::distanceToTruth;
using test::observe;
using test::ofClass;

Vec3 centre(const MapInstance& m) {
  Vec3 c = Vec3::Zero();
  for (const auto& p : m.points) c += p;
  return c / double(m.points.size());
}

Observation line(CrowdClass cls, int drive, Vec3 a, Vec3 b) {
  Observation o;
  o.cls = cls;
  o.drive = drive;
  o.points = {a, b};
  return o;
}

}  // namespace

TEST_CASE("a grid cell takes the class with the most votes, with at least min_votes",
          "[aggregate][grid_vote]") {
  // three lane observations along x and two stop-line observations along y cross at (1.05, 1.05)
  std::vector<Observation> items;
  for (int d = 0; d < 3; ++d)
    items.push_back(line(CrowdClass::kLaneLine, d, {0, 1.05, 0}, {2, 1.05, 0}));
  for (int d = 3; d < 5; ++d)
    items.push_back(line(CrowdClass::kStopLine, d, {1.05, 0, 0}, {1.05, 2, 0}));
  GridVoteParams p;  // 0.1 m cells
  const VoteGrid grid = voteGrid(items, {0, 1, 2, 3, 4}, p);
  const int64_t crossing = VoteGrid::key(10, 10);
  REQUIRE(grid.cells().count(crossing) == 1);
  const GridCell& cell = grid.cells().at(crossing);
  CHECK(cell.votes[std::size_t(CrowdClass::kLaneLine)] == 3);  // one vote per drive
  CHECK(cell.votes[std::size_t(CrowdClass::kStopLine)] == 2);
  CHECK(VoteGrid::winner(cell, 3) == CrowdClass::kLaneLine);
  CHECK(VoteGrid::winner(cell, 4) == std::nullopt);  // the majority has too few votes
  // away from the crossing each line holds its own votes only
  CHECK(VoteGrid::winner(grid.cells().at(VoteGrid::key(10, 2)), 2) == CrowdClass::kStopLine);
  CHECK(VoteGrid::winner(grid.cells().at(VoteGrid::key(2, 10)), 2) == CrowdClass::kLaneLine);
  // a drive that saw the stop line twice still votes once
  items.push_back(line(CrowdClass::kStopLine, 4, {1.05, 0.5, 0}, {1.05, 1.5, 0}));
  const VoteGrid twice = voteGrid(items, {0, 1, 2, 3, 4, 5}, p);
  CHECK(twice.cells().at(crossing).votes[std::size_t(CrowdClass::kStopLine)] == 2);
  // the majority flips with the votes of two more drives
  items.push_back(line(CrowdClass::kStopLine, 5, {1.05, 0, 0}, {1.05, 2, 0}));
  items.push_back(line(CrowdClass::kStopLine, 6, {1.05, 0, 0}, {1.05, 2, 0}));
  const VoteGrid more = voteGrid(items, {0, 1, 2, 3, 4, 5, 6, 7}, p);
  CHECK(more.cells().at(crossing).votes[std::size_t(CrowdClass::kStopLine)] == 4);
  CHECK(VoteGrid::winner(more.cells().at(crossing), 3) == CrowdClass::kStopLine);
}

TEST_CASE("grid voting recovers the lines of a three-line road with their attributes",
          "[aggregate][grid_vote]") {
  test::SynthOptions o;
  o.discrete = false;
  const auto w = test::makeSynthWorld(o);
  AggregatorStats stats;
  const VectorMap map = aggregateObservations(observe(w), gridVote(), &stats);
  const auto lanes = ofClass(map, CrowdClass::kLaneLine);
  REQUIRE(lanes.size() == 3);
  CHECK(stats.grid.cells > 0);
  CHECK(stats.grid.voted_cells > 0);
  CHECK(stats.grid.min_votes_used == 3);
  double covered = 0;
  std::size_t points = 0, typical = 0;
  for (const auto* l : lanes) {
    covered += polylineLength(l->points);
    for (const auto& p : l->points) {
      const double d = distanceToTruth(p, w.truth, CrowdClass::kLaneLine);
      CHECK(d < kLanePointTolerance);
      ++points;
      typical += d < kLanePointTypical;
    }
    // the cells' attribute votes: the middle line is dashed, the y = 7 line yellow
    const double y = l->points.front().y();
    CHECK(l->attributes.style == (std::abs(y - 3.5) < 1 ? LineStyle::kDashed : LineStyle::kSolid));
    CHECK(l->attributes.color == (std::abs(y - 7) < 1 ? LineColor::kYellow : LineColor::kWhite));
    CHECK(l->support.drives <= o.drives);
  }
  CHECK(double(typical) >= kTypicalShare * double(points));
  CHECK(covered >= kMinCoverage * 3 * o.length);
  CHECK(covered <= 1.05 * 3 * o.length);
}

TEST_CASE("grid voting finds the stop line and arrows, elevated classes as the default method",
          "[aggregate][grid_vote]") {
  test::SynthOptions o;
  const auto w = test::makeSynthWorld(o);
  const auto set = observe(w);
  const VectorMap grid = aggregateObservations(set, gridVote());
  const VectorMap ours = aggregateObservations(set, AggregatorParams{});
  // (the synthetic crosswalk is crossed by a lane line painted through it: the line's cells cut
  // it in two, as they would any grid-voted crosswalk; not checked here)
  for (CrowdClass c : {CrowdClass::kStopLine, CrowdClass::kGroundArrow}) {
    INFO(crowdClassName(c));
    const auto truth = ofClass(w.truth, c);
    const auto got = ofClass(grid, c);
    REQUIRE(got.size() == truth.size());
    for (const auto* t : truth) {
      double best = 1e300;
      for (const auto* g : got) best = std::min(best, (centre(*g) - centre(*t)).norm());
      CHECK(best < kDiscreteTolerance);
    }
  }
  for (CrowdClass c : {CrowdClass::kTrafficSign, CrowdClass::kTrafficLight, CrowdClass::kPole}) {
    INFO(crowdClassName(c));
    const auto a = ofClass(grid, c), b = ofClass(ours, c);
    REQUIRE(a.size() == b.size());
    for (std::size_t i = 0; i < a.size(); ++i) CHECK(a[i]->points == b[i]->points);
  }
}

TEST_CASE("grid voting refuses observations that would paint too many cells",
          "[aggregate][grid_vote][errors]") {
  std::vector<Observation> items(1);
  items[0].cls = CrowdClass::kCrosswalk;
  items[0].element_id = 7;
  items[0].points = {{0, 0, 0}, {5000, 0, 0}, {5000, 5000, 0}, {0, 5000, 0}};
  try {
    voteGrid(items, {0}, GridVoteParams{});
    FAIL("a 5 km crosswalk was painted");
  } catch (const InputError& e) {
    CHECK_THAT(e.what(), Catch::Contains("grid cells"));
    CHECK_THAT(e.what(), Catch::Contains("element 7"));
  }
}
