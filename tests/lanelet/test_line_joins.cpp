// Lane lines broken by aggregation (issue 35): lanelet/joins.hpp and its effect on the plan.
#include <catch2/catch.hpp>

#include <algorithm>

#include "lane_fixtures.hpp"
#include "lanelet/joins.hpp"
#include "mapfuse/lanelet/plan.hpp"

using namespace mapfuse;
using Vec3 = Eigen::Vector3d;
using test::Line;
using test::mapOf;
using test::requireNoDegenerateConnector;
using test::straight;

namespace {

/// Where lanelet ll's left (or right) bound ends (or starts) in its travel direction.
Vec3 boundPoint(const lanelet::LaneletPlan& plan, const lanelet::LaneletPlan::Lanelet& ll,
                bool left, bool at_end) {
  const auto [piece, last] = lanelet::boundEnd(plan, ll, left, at_end);
  const auto pts = lanelet::piecePoints(plan, piece);
  return last ? pts.back() : pts.front();
}

/// The plan's lanelets in order of their centre's start x.
std::vector<lanelet::LaneletPlan::Lanelet> byX(const lanelet::LaneletPlan& plan) {
  auto out = plan.lanelets;
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) {
    return a.centre.front().x() < b.centre.front().x();
  });
  return out;
}

/// Lanelet2 routes from a to b only where a's bounds end on the nodes where b's begin.
void requireSharedEnds(const lanelet::LaneletPlan& plan, const lanelet::LaneletPlan::Lanelet& a,
                       const lanelet::LaneletPlan::Lanelet& b) {
  for (const bool left : {true, false})
    CHECK((boundPoint(plan, a, left, true) - boundPoint(plan, b, left, false)).norm() < 1e-9);
}

/// The plan of one lane, its lines given, driven east along y = 1.75 m: two one-way lanelets
/// that Lanelet2 can route from the first to the second. Returns the plan.
lanelet::LaneletPlan oneLaneInTwo(const std::vector<Line>& lines) {
  const lanelet::DrivePath east = {{0.0, 1.75, 0.0}, {60.0, 1.75, 0.0}};
  const auto plan = lanelet::planLanelets(mapOf(lines), {east});
  CHECK(plan.line_ends_joined == 1);
  const auto lanes = byX(plan);
  REQUIRE(lanes.size() == 2);
  CHECK(lanes[0].direction_known);
  CHECK(lanes[1].direction_known);
  requireSharedEnds(plan, lanes[0], lanes[1]);
  requireNoDegenerateConnector(plan);
  return plan;
}

}  // namespace

TEST_CASE("line joins: a gap in one lane line leaves consecutive lanelets on shared nodes",
          "[lanelet]") {
  // Seed 13 (8 %), x = 610 m: the right line of a lane ends, the next instance begins 0.9 m on;
  // the left line runs on. Before the joins the two lanelets met at one node on the left and
  // 0.9 m apart on the right, and the drive's sample in the sliver between them made a connector
  // whose left bound was a single node: Lanelet2 found no route from one lanelet to the next.
  const auto plan =
      oneLaneInTwo({straight(0.0, 0.0, 28.7), straight(0.0, 29.6, 60.0), straight(3.5, 0.0, 60.0)});
  CHECK(plan.connectors.empty());  // none needed: the lanelets follow each other
}

TEST_CASE("line joins: an overlap of two pieces of one lane line is trimmed to one end node",
          "[lanelet]") {
  // Fragments of 5-6 m that overlap their neighbours by 1-2.5 m (seed 13, x = 615 m), 0.1 m apart.
  oneLaneInTwo({straight(0.0, 0.0, 31.0), straight(0.1, 29.0, 60.0), straight(3.5, 0.0, 60.0)});
}

TEST_CASE("line joins: the lanelet after a gap is kept when a third line starts beside it",
          "[lanelet]") {
  // Seed 13 (8 %), the 169 m S-bend at x = 1340 m: the right line P ends and Q begins 0.5 m on,
  // and the line across the centre line X begins 1.15 m after P's end. X got a cut at P's end and
  // one at the far line's start; Q's start lay nearer the first, so Q's whole length matched two
  // pieces of X and the lanelet was dropped (unmatched_pieces): 210 m of drive on no lanelet.
  const Line p = straight(-3.5, 0.0, 28.7), q = straight(-3.5, 29.2, 100.0);
  const Line far = straight(3.5, 29.85, 100.0), x = straight(0.0, 0.0, 100.0);
  const VectorMap map = mapOf({p, q, far, x});
  const lanelet::DrivePath drive = {{0.0, -1.75, 0.0}, {100.0, -1.75, 0.0}};
  const auto plan = lanelet::planLanelets(map, {drive});
  CHECK(plan.unmatched_pieces == 0);
  std::vector<lanelet::LaneletPlan::Lanelet> right_lane;  // lanelets bounded by P or Q
  for (const auto& ll : byX(plan))
    for (const std::size_t piece : {ll.left, ll.right})
      if (plan.lines[plan.pieces[piece].line].instance <= 1) right_lane.push_back(ll);
  REQUIRE(right_lane.size() == 2);
  CHECK(plan.lines[plan.pieces[right_lane[1].right].line].instance == 1);  // Q bounds the second
  requireSharedEnds(plan, right_lane[0], right_lane[1]);
}

TEST_CASE("line joins: ends that do not continue one line stay apart", "[lanelet]") {
  using lanelet::detail::joinLineEnds;
  // A gap: both lines end at the midpoint, bridged by one segment each.
  std::vector<Line> gap = {straight(0.0, 0.0, 10.0), straight(0.2, 11.0, 20.0)};
  REQUIRE(joinLineEnds(gap, 3.0).joined == 1);
  CHECK((gap[0].back() - Vec3(10.5, 0.1, 0.0)).norm() < 1e-9);
  CHECK((gap[1].front() - Vec3(10.5, 0.1, 0.0)).norm() < 1e-9);
  CHECK(gap[0].size() == 12);  // 0..10 and the joint
  // An overlap: the vertices beyond the midpoint go.
  std::vector<Line> overlap = {straight(0.0, 0.0, 10.0), straight(0.0, 8.0, 20.0)};
  const auto stats = joinLineEnds(overlap, 3.0);
  CHECK(stats.max_overlap == Approx(2.0));
  CHECK(overlap[0].back().x() == Approx(9.0));
  CHECK(overlap[1].front().x() == Approx(9.0));
  for (const auto& v : overlap[0]) CHECK(v.x() <= 9.0 + 1e-9);
  // Beyond max_join, or 0 (off).
  std::vector<Line> far = {straight(0.0, 0.0, 10.0), straight(0.0, 13.5, 20.0)};
  CHECK(joinLineEnds(far, 3.0).joined == 0);
  std::vector<Line> off = {straight(0.0, 0.0, 10.0), straight(0.0, 10.5, 20.0)};
  CHECK(joinLineEnds(off, 0.0).joined == 0);
  // A lane apart (the next lane's line begins across), and at right angles (a corner).
  std::vector<Line> across = {straight(0.0, 0.0, 10.0), straight(3.5, 10.5, 20.0)};
  CHECK(joinLineEnds(across, 3.0).joined == 0);
  std::vector<Line> corner = {straight(0.0, 0.0, 10.0), {{10.5, 0.5, 0.0}, {10.5, 10.0, 0.0}}};
  CHECK(joinLineEnds(corner, 3.0).joined == 0);
  // Three fragments in a row: each facing pair once; the middle one is joined at both ends.
  std::vector<Line> chain = {straight(0.0, 0.0, 10.0), straight(0.0, 10.4, 16.0),
                             straight(0.0, 14.5, 30.0)};
  CHECK(joinLineEnds(chain, 3.0).joined == 2);
  CHECK((chain[0].back() - chain[1].front()).norm() < 1e-9);
  CHECK((chain[1].back() - chain[2].front()).norm() < 1e-9);
}
