// Change detection against a hand-made truth: a straight road, a map, and drives that saw a
// known set of changes (docs/update.md).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "mapfuse/core/error.hpp"
#include "mapfuse/update/change_detection.hpp"

namespace mapfuse {
namespace {

const geo::GeoOrigin kOrigin{49.0, 8.4, 110.0};
constexpr double kRoadLength = 200.0;  // m, the drives run along +x (east) at y = 0

MapInstance pole(int64_t id, double x, double y) {
  MapInstance m;
  m.id = id;
  m.cls = CrowdClass::kPole;
  m.points = {Eigen::Vector3d(x, y, 0)};
  m.height = 4;
  return m;
}

MapInstance laneLine(int64_t id, double y, LineStyle style) {
  MapInstance m;
  m.id = id;
  m.cls = CrowdClass::kLaneLine;
  m.attributes = {style, LineColor::kWhite};
  for (double x = 0; x <= kRoadLength; x += 1.0) m.points.emplace_back(x, y, 0);
  return m;
}

// Ids: 1 pole kept, 2 pole removed, 3 pole moved, 4 pole far off the road (never in view),
// 10 solid line re-striped over x in [60, 120], 11 dashed line painted solid.
VectorMap beforeMap() {
  VectorMap map;
  map.origin = kOrigin;
  map.instances = {pole(1, 50, 6),
                   pole(2, 100, 6),
                   pole(3, 150, -6),
                   pole(4, 100, 40),
                   laneLine(10, -1.75, LineStyle::kSolid),
                   laneLine(11, 1.75, LineStyle::kDashed)};
  return map;
}

// One drive over the changed world: keyframes every 8 m, identity attitude, elements anchored
// to keyframe 0 at the origin (body = ENU).
Lsm drive(const std::string& id) {
  Lsm lsm;
  lsm.drive_id = id;
  lsm.frame = LsmFrame::kEnu;
  lsm.origin = kOrigin;
  for (int k = 0; k * 8.0 <= kRoadLength; ++k) {
    Keyframe kf;
    kf.id = k;
    kf.stamp = k;
    kf.T_frame_body.translation() = Eigen::Vector3d(k * 8.0, 0, 0);
    lsm.keyframes.push_back(kf);
  }
  auto add = [&](CrowdClass cls, std::vector<Eigen::Vector3d> pts, LineStyle style) {
    Element e;
    e.id = int64_t(lsm.elements.size());
    e.cls = cls;
    e.attributes = {style, cls == CrowdClass::kLaneLine ? LineColor::kWhite : LineColor::kNone};
    e.points_body = std::move(pts);
    e.covariances.assign(e.points_body.size(), Eigen::Matrix3d::Identity() * 1e-4);
    e.confidence = 0.9;
    e.height = cls == CrowdClass::kPole ? 4.0 : 0.0;
    lsm.elements.push_back(e);
  };
  add(CrowdClass::kPole, {{50.1, 6.0, 0}}, LineStyle::kNone);    // kept
  add(CrowdClass::kPole, {{152.5, -6.0, 0}}, LineStyle::kNone);  // moved 2.5 m
  add(CrowdClass::kPole, {{80.0, -7.0, 0}}, LineStyle::kNone);   // added
  for (double x0 = 0; x0 < kRoadLength; x0 += 20) {              // lines in 20 m pieces
    std::vector<Eigen::Vector3d> shifted, solid;
    for (double x = x0; x <= x0 + 20; x += 0.75) {
      shifted.emplace_back(x, x >= 60 && x <= 120 ? -0.75 : -1.75, 0);
      solid.emplace_back(x, 1.75, 0);
    }
    add(CrowdClass::kLaneLine, shifted, LineStyle::kSolid);
    add(CrowdClass::kLaneLine, solid, LineStyle::kSolid);
  }
  return lsm;
}

// The drives here are in the map's frame by construction; registration to the map (tested in
// test_map_registration.cpp) would move them by the 0.1 m of the kept pole's observation, the
// only along-road landmark, and the expected geometry below is exact.
update::UpdateSettings detectionOnly() {
  update::UpdateSettings s;
  s.registration.enabled = false;
  return s;
}

const MapChange* changeOf(const MapChanges& changes, int64_t before_id) {
  for (const auto& c : changes.changes)
    if (c.before && c.before->id == before_id) return &c;
  return nullptr;
}

}  // namespace

TEST_CASE("update detects each kind of change from three traversals", "[update]") {
  const VectorMap map = beforeMap();
  const std::vector<Lsm> drives = {drive("a"), drive("b"), drive("c")};
  const update::UpdateResult r =
      update::detectChanges(map, drives, {"a.json", "b.json", "c.json"}, detectionOnly());
  const auto& c = r.changes.changes;
  REQUIRE(c.size() == 5);  // removed, moved, restriped, retyped, added; pole 1 confirmed
  CHECK(changeOf(r.changes, 1) == nullptr);
  const MapChange* removed = changeOf(r.changes, 2);
  REQUIRE(removed);
  CHECK(removed->kind == ChangeKind::kRemoved);
  CHECK(removed->supporting_traversals.size() == 3);
  // three misses at Pd 0.95 (a map without support counts), Pfa 0.02, prior 0.03:
  // l = -3.48 + 3 * 2.98 = 5.45
  CHECK(*removed->confidence == Approx(1 / (1 + std::exp(-5.4505))).margin(1e-3));
  const MapChange* moved = changeOf(r.changes, 3);
  REQUIRE(moved);
  CHECK(moved->kind == ChangeKind::kMoved);
  CHECK(moved->after->points[0].x() == Approx(152.5).margin(1e-9));  // the median displacement
  const MapChange* restriped = changeOf(r.changes, 10);
  REQUIRE(restriped);
  CHECK(restriped->kind == ChangeKind::kRestriped);
  // the stretch moved 1 m to the left (+y) as the drives saw it, the rest kept
  const auto yAt = [](const MapInstance& m, double x) {
    const auto it = std::min_element(
        m.points.begin(), m.points.end(),
        [x](const auto& a, const auto& b) { return std::abs(a.x() - x) < std::abs(b.x() - x); });
    return it->y();
  };
  CHECK(yAt(*restriped->after, 90) == Approx(-0.75).margin(0.02));
  CHECK(yAt(*restriped->after, 20) == Approx(-1.75).margin(1e-9));
  CHECK(yAt(*restriped->after, 180) == Approx(-1.75).margin(1e-9));
  const MapChange* retyped = changeOf(r.changes, 11);
  REQUIRE(retyped);
  CHECK(retyped->kind == ChangeKind::kRetyped);
  CHECK(retyped->after->attributes.style == LineStyle::kSolid);
  const auto added = std::find_if(c.begin(), c.end(),
                                  [](const MapChange& x) { return x.kind == ChangeKind::kAdded; });
  REQUIRE(added != c.end());
  CHECK(added->cls == CrowdClass::kPole);
  CHECK((added->after->points[0] - Eigen::Vector3d(80, -7, 0)).norm() < 1e-9);
  CHECK(added->after->id > 11);
  // the pole 40 m beside the road was in no camera view: not verified, never removed
  CHECK(r.stats.not_verified == std::vector<int64_t>{4});
}

TEST_CASE("update removes nothing on one missed observation", "[update]") {
  // one traversal that missed pole 2: l = -3.48 + 2.98 < 0, no removal (a 5 % miss is likelier
  // than a 3 % removal); the element is in view, neither confirmed nor changed
  const update::UpdateResult r =
      update::detectChanges(beforeMap(), {drive("a")}, {"a.json"}, detectionOnly());
  CHECK(changeOf(r.changes, 2) == nullptr);
  CHECK(r.stats.undecided == 1);
  // with a prior of 0.2 the same miss is a removal
  update::UpdateSettings eager = detectionOnly();
  eager.decision.removal_prior = 0.2;
  const auto r2 = update::detectChanges(beforeMap(), {drive("a")}, {"a.json"}, eager);
  REQUIRE(changeOf(r2.changes, 2));
  CHECK(changeOf(r2.changes, 2)->kind == ChangeKind::kRemoved);
}

TEST_CASE("update refuses drives outside the map's frame", "[update]") {
  Lsm other = drive("a");
  other.origin = geo::GeoOrigin{49.1, 8.4, 110.0};
  CHECK_THROWS_AS(update::detectChanges(beforeMap(), {other}, {"a.json"}, detectionOnly()),
                  InputError);
  Lsm odom = drive("a");
  odom.frame = LsmFrame::kOdom;
  CHECK_THROWS_WITH(update::detectChanges(beforeMap(), {odom}, {"a.json"}, detectionOnly()),
                    Catch::Contains("a.json"));
}

}  // namespace mapfuse
