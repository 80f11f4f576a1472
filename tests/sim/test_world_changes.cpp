// Changed worlds (issue 34, docs/simulate.md "Changed worlds"): the requested number of changes
// of each kind, every other element untouched (id, geometry, attributes), moves and shifts
// within their configured ranges, additions at plausible places; on the procedural world and
// on the Lanelet2 and OpenDRIVE map worlds.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <set>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/map_changes_io.hpp"
#include "mapfuse/sim/crowd.hpp"
#include "mapfuse/sim/map_world.hpp"
#include "mapfuse/sim/polyline.hpp"
#include "mapfuse/sim/world_changes.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;

namespace {
constexpr double kExact = 1e-9;     // m, rigid moves and reflections: arithmetic only
constexpr double kChordSag = 1e-3;  // m, a 1 m chord of the 8 % terrain to its surface (< 1e-5)
constexpr double kShiftTolerance = 0.05;  // m, a vertex-normal offset measured to the old line
// m, a turned arrow stays in place: its extent's centre, about which it turns, is 0.21 m from the
// mean of the template's vertices (sim/world_changes.cpp kArrowShape)
constexpr double kArrowCentre = 0.25;

sim::World proceduralWorld() {
  const sim::CrowdSettings settings;
  return sim::proceduralWorld(settings, geo::GeoOrigin{49.0, 8.4, 110.0});
}

sim::ChangeSettings everyKind(int n) {
  sim::ChangeSettings s;
  s.removed = s.added = s.moved = s.restriped = s.retyped = n;
  s.seed = 11;
  return s;
}

const MapInstance* findId(const VectorMap& map, int64_t id) {
  for (const auto& m : map.instances)
    if (m.id == id) return &m;
  return nullptr;
}

bool same(const MapInstance& a, const MapInstance& b) {
  return a.id == b.id && a.cls == b.cls && a.points == b.points && a.attributes == b.attributes &&
         a.height == b.height && a.note == b.note && a.source_ids == b.source_ids;
}

/// Height of p above the world's ground (its z where the world has no surface).
double aboveGround(const sim::World& world, const Eigen::Vector3d& p) {
  return world.surface_height ? p.z() - world.surface_height(p) : p.z();
}

/// Horizontal displacement of a rigidly moved element; fails if the move is not rigid in the
/// ground plane or a point's height above the ground changed.
double rigidShift(const MapInstance& before, const MapInstance& after, const sim::World& world) {
  REQUIRE(before.points.size() == after.points.size());
  const Eigen::Vector2d d = (after.points[0] - before.points[0]).head<2>();
  for (std::size_t i = 0; i < before.points.size(); ++i) {
    CHECK((after.points[i] - before.points[i]).head<2>().isApprox(d, kExact));
    CHECK(std::abs(aboveGround(world, after.points[i]) - aboveGround(world, before.points[i])) <
          kExact);
  }
  return d.norm();
}

double largestOffset(const MapInstance& before, const MapInstance& after) {
  double worst = 0.0;
  for (const auto& p : after.points)
    worst = std::max(worst, sim::distanceToPolyline(before.points, p));
  return worst;
}

void checkRetyped(const MapChange& c) {
  if (c.cls == CrowdClass::kLaneLine) {
    CHECK(c.after->points == c.before->points);
    CHECK(c.after->attributes.style != c.before->attributes.style);
    CHECK(c.after->attributes.style != LineStyle::kNone);
    return;
  }
  REQUIRE(c.cls == CrowdClass::kGroundArrow);  // turned round: p + p' is the same everywhere
  const Eigen::Vector3d sum0 = c.before->points[0] + c.after->points[0];
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < c.before->points.size(); ++i) {
    CHECK((c.before->points[i] + c.after->points[i] - sum0).head<2>().norm() < kExact);
    mean += c.before->points[i];
  }
  mean /= double(c.before->points.size());
  CHECK((0.5 * sum0 - mean).head<2>().norm() < kArrowCentre);
  CHECK(c.after->points != c.before->points);
}

/// An addition stands clear of every element of its class and, as a sign or pole, off the lanes.
void checkAdded(const MapChange& c, const sim::World& before) {
  const Eigen::Vector3d centre = instanceCentre(*c.after);
  for (const auto& m : before.truth.instances)
    if (m.cls == c.cls)
      CHECK((instanceCentre(m) - centre).head<2>().norm() >= sim::kAddedClearance);
  double nearest_lane = 1e18, width = 0.0;
  for (const auto& lane : before.lanes) {
    const double d = sim::distanceToPolyline(lane.centerline, centre);
    if (d < nearest_lane) nearest_lane = d, width = lane.width;
  }
  if (c.cls == CrowdClass::kPole || c.cls == CrowdClass::kTrafficSign)
    CHECK(nearest_lane >= 0.5 * width);
  else  // an arrow in a lane, a stop line across one
    CHECK(nearest_lane < 0.1);
}

/// Applies `s` to a copy of `world` and checks every promise of applyWorldChanges.
MapChanges checkChanges(const sim::World& world, const sim::ChangeSettings& s) {
  sim::World after = world;
  const MapChanges changes = sim::applyWorldChanges(after, s);
  std::map<ChangeKind, int> by_kind;
  std::set<int64_t> named;
  int64_t largest_before = 0;
  for (const auto& m : world.truth.instances) largest_before = std::max(largest_before, m.id);
  for (const auto& c : changes.changes) {
    ++by_kind[c.kind];
    if (c.before) {
      CHECK(named.insert(c.before->id).second);
      const MapInstance* old = findId(world.truth, c.before->id);
      REQUIRE(old != nullptr);
      CHECK(same(*old, *c.before));
    }
    const MapInstance* now = c.after ? findId(after.truth, c.after->id) : nullptr;
    if (c.after) REQUIRE(now != nullptr);
    if (c.after) CHECK(same(*now, *c.after));
    switch (c.kind) {
      case ChangeKind::kRemoved:
        CHECK(c.cls != CrowdClass::kLaneLine);
        CHECK(findId(after.truth, c.before->id) == nullptr);
        break;
      case ChangeKind::kAdded:
        CHECK(c.after->id > largest_before);
        checkAdded(c, world);
        break;
      case ChangeKind::kMoved: {
        CHECK((c.cls == CrowdClass::kPole || c.cls == CrowdClass::kTrafficSign));
        const double d = rigidShift(*c.before, *c.after, world);
        CHECK(d >= s.move_min - kExact);
        CHECK(d <= s.move_max + kExact);
        break;
      }
      case ChangeKind::kRestriped: {
        CHECK(c.cls == CrowdClass::kLaneLine);
        const double d = largestOffset(*c.before, *c.after);
        CHECK(d >= s.shift_min - kShiftTolerance);
        CHECK(d <= s.shift_max + kShiftTolerance);
        break;
      }
      case ChangeKind::kRetyped: checkRetyped(c); break;
    }
  }
  CHECK(by_kind[ChangeKind::kRemoved] == s.removed);
  CHECK(by_kind[ChangeKind::kAdded] == s.added);
  CHECK(by_kind[ChangeKind::kMoved] == s.moved);
  CHECK(by_kind[ChangeKind::kRestriped] == s.restriped);
  CHECK(by_kind[ChangeKind::kRetyped] == s.retyped);
  // Every element no change names is still there, untouched.
  int untouched = 0;
  for (const auto& m : world.truth.instances) {
    if (named.count(m.id)) continue;
    const MapInstance* now = findId(after.truth, m.id);
    REQUIRE(now != nullptr);
    CHECK(same(*now, m));
    ++untouched;
  }
  CHECK(after.truth.instances.size() ==
        world.truth.instances.size() - std::size_t(s.removed) + std::size_t(s.added));
  CHECK(untouched ==
        int(world.truth.instances.size()) - s.removed - s.moved - s.restriped - s.retyped);
  return changes;
}

}  // namespace

TEST_CASE("changes on the procedural world: counts and untouched elements and ranges", "[sim]") {
  const sim::World world = proceduralWorld();
  const MapChanges changes = checkChanges(world, everyKind(8));
  CHECK(changes.changes.size() == 40);
  // Both classes of retyping and every class of addition occur over a few seeds.
  std::set<std::pair<ChangeKind, CrowdClass>> seen;
  for (uint64_t seed = 1; seed <= 6; ++seed) {
    sim::ChangeSettings s = everyKind(6);
    s.seed = seed;
    for (const auto& c : checkChanges(world, s).changes) seen.insert({c.kind, c.cls});
  }
  for (const CrowdClass cls : {CrowdClass::kTrafficSign, CrowdClass::kPole,
                               CrowdClass::kGroundArrow, CrowdClass::kStopLine})
    CHECK(seen.count({ChangeKind::kAdded, cls}) == 1);
  CHECK(seen.count({ChangeKind::kRetyped, CrowdClass::kGroundArrow}) == 1);
  CHECK(seen.count({ChangeKind::kRetyped, CrowdClass::kLaneLine}) == 1);
}

TEST_CASE("changes are deterministic in their seed and independent of the rest", "[sim]") {
  const sim::World world = proceduralWorld();
  const auto draw = [&](uint64_t seed) {
    sim::World w = world;
    sim::ChangeSettings s = everyKind(5);
    s.seed = seed;
    return io::mapChangesToJson(sim::applyWorldChanges(w, s));
  };
  CHECK(draw(3) == draw(3));
  CHECK(draw(3) != draw(4));
  sim::World unchanged = world;  // no change requested: the world stays as it is
  CHECK(sim::applyWorldChanges(unchanged, {}).changes.empty());
  REQUIRE(unchanged.truth.instances.size() == world.truth.instances.size());
  for (std::size_t i = 0; i < world.truth.instances.size(); ++i)
    CHECK(same(unchanged.truth.instances[i], world.truth.instances[i]));
}

TEST_CASE("more changes than the world has candidates is a config error naming the key", "[sim]") {
  sim::World world = proceduralWorld();
  sim::ChangeSettings s;
  s.moved = 100000;
  CHECK_THROWS_AS(sim::applyWorldChanges(world, s), ConfigError);
  try {
    sim::applyWorldChanges(world, s);
  } catch (const ConfigError& e) {
    CHECK_THAT(e.what(), Catch::Contains("change_moved") && Catch::Contains("100000"));
  }
}

TEST_CASE("changes on the Lanelet2 Karlsruhe map world", "[sim][lanelet2]") {
  const auto path = test::requireShared("data/maps/lanelet2_karlsruhe_mapping_example.osm");
  geo::GeoOrigin origin{49.0, 8.4, 110.0};
  const sim::World world = sim::loadMapWorld(path.string(), true, {}, &origin);
  checkChanges(world, everyKind(5));
}

TEST_CASE("changes on the OpenDRIVE MONAEast map world", "[sim][opendrive]") {
  const auto path = test::requireShared("data/maps/MONAEast.xodr");
  geo::GeoOrigin origin{49.0, 8.4, 110.0};
  const sim::World world = sim::loadMapWorld(path.string(), true, {}, &origin);
  sim::ChangeSettings s = everyKind(5);
  s.moved = s.removed = 0;  // the map's world has lane lines only: nothing to move or remove
  checkChanges(world, s);
}

TEST_CASE("drives over a changed world observe the changed truth", "[sim]") {
  sim::World world = proceduralWorld();
  sim::ChangeSettings s;
  s.removed = 40;
  s.moved = 10;
  s.seed = 5;
  const MapChanges changes = sim::applyWorldChanges(world, s);
  std::set<int64_t> removed, ids;
  for (const auto& c : changes.changes)
    if (c.kind == ChangeKind::kRemoved) removed.insert(c.before->id);
  for (const auto& m : world.truth.instances) ids.insert(m.id);
  sim::CrowdSettings settings;
  settings.traversals = 4;
  const geo::GeoOrigin origin{49.0, 8.4, 110.0};
  const sim::Crowd crowd(world, origin, settings);
  int observed = 0;
  for (int i = 0; i < settings.traversals; ++i)
    for (const auto& e : crowd.traversal(i).observed.lsm.elements) {
      if (e.truth_id < 0) continue;  // an injected false positive
      ++observed;
      CHECK(removed.count(e.truth_id) == 0);
      CHECK(ids.count(e.truth_id) == 1);
    }
  CHECK(observed > 100);
}

TEST_CASE("changes on a hilly world keep every element on the ground", "[sim]") {
  sim::CrowdSettings settings;
  settings.world.hill_grade = 0.08;
  const sim::World world = sim::proceduralWorld(settings, geo::GeoOrigin{49.0, 8.4, 110.0});
  REQUIRE(world.surface_height);
  const MapChanges changes = checkChanges(world, everyKind(8));
  for (const auto& c : changes.changes) {
    if (!c.after) continue;
    for (std::size_t i = 0; i < c.after->points.size(); ++i) {
      const double h = aboveGround(world, c.after->points[i]);
      if (c.kind == ChangeKind::kRestriped) {  // on the ground; a stretch is resampled at 1 m,
        CHECK(std::abs(h) < kChordSag);        // its chords off the curved terrain
      } else if (c.before) {                   // moved, retyped: as high above the ground as before
        CHECK(std::abs(h - aboveGround(world, c.before->points[i])) < kExact);
      } else if (c.cls == CrowdClass::kTrafficSign) {  // a plate 2.0-2.6 m up (placed from
        // a point of the lane's centre line: its chords too)
        CHECK((std::abs(h - 2.0) < kChordSag || std::abs(h - 2.6) < kChordSag));
      } else {  // a pole's base, an arrow, a stop line: on the road surface
        CHECK(std::abs(h) < kChordSag);
      }
    }
  }
}
