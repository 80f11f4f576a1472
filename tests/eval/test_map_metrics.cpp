#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include "mapfuse/eval/error_stats.hpp"
#include "mapfuse/eval/map_metrics.hpp"
#include "mapfuse/eval/scored_truth.hpp"
#include "mapfuse/io/lsm_io.hpp"
#include "mapfuse/geo/origin.hpp"
#include "mapfuse/stages/evaluate_map.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;
using namespace mapfuse::eval;
using Vec3 = Eigen::Vector3d;

namespace {

constexpr double kExact = 1e-9;  // metrics of hand-made maps are exact up to rounding

// A straight line at height 0 along +x at `y`, from x0 to x0 + length, 11 points.
std::vector<Vec3> line(double y, double length = 100.0, double x0 = 0.0) {
  std::vector<Vec3> p;
  for (int i = 0; i <= 10; ++i) p.push_back({x0 + length * i / 10.0, y, 0.0});
  return p;
}

MapInstance inst(int64_t id, CrowdClass c, std::vector<Vec3> pts, double h = 0) {
  MapInstance m;
  m.id = id;
  m.cls = c;
  m.points = std::move(pts);
  m.height = h;
  return m;
}

// A map of `instances` in ENU of the tests' origin.
VectorMap mapOf(std::vector<MapInstance> instances) {
  VectorMap t;
  t.origin = {49.0, 8.4, 110.0};
  t.instances = std::move(instances);
  return t;
}

// three parallel lane lines 3.5 m apart, 100 m long; poles at x = 0, 20, 50 (y = -3)
VectorMap truthMap() {
  return mapOf(
      {inst(1, CrowdClass::kLaneLine, line(0)), inst(2, CrowdClass::kLaneLine, line(3.5)),
       inst(3, CrowdClass::kLaneLine, line(7)), inst(4, CrowdClass::kPole, {{0, -3, 0}}, 6),
       inst(5, CrowdClass::kPole, {{20, -3, 0}}, 6), inst(6, CrowdClass::kPole, {{50, -3, 0}}, 6)});
}

// Poses every 1 m along +x from x = 0 to x = 100, heading east.
std::vector<Pose3> driveAlongX() {
  std::vector<Pose3> poses;
  for (int i = 0; i <= 100; ++i) poses.push_back(Pose3(Eigen::Translation3d(i, 0.0, 0.0)));
  return poses;
}

const ClassMetrics& get(const MapMetrics& m, CrowdClass c) {
  for (const auto& x : m.classes)
    if (x.cls == c) return x;
  FAIL("class missing");
  throw 0;
}

}  // namespace

TEST_CASE("error statistics: mean, RMS, 3-sigma quantile", "[eval]") {
  const auto s = errorStats({0.3, 0.0, 0.0});
  CHECK(s.count == 3);
  CHECK(s.mean == Approx(0.1).margin(kExact));
  CHECK(s.rms == Approx(std::sqrt(0.03)).margin(kExact));
  CHECK(s.p3sigma == Approx(0.3).margin(kExact));
  CHECK(s.max == Approx(0.3).margin(kExact));
  std::vector<double> many(1000, 1.0);
  many[0] = 50.0;  // one outlier in 1000 is beyond the 99.73 % quantile
  CHECK(errorStats(many).p3sigma == Approx(1.0));
  CHECK(errorStats({}).count == 0);
}

TEST_CASE("the truth against itself is perfect", "[eval][map]") {
  const auto m = evaluateMap(truthMap(), truthMap(), MapEvalParams{});
  for (const auto& c : m.classes) {
    INFO(crowdClassName(c.cls));
    CHECK(c.completeness == Approx(1.0).margin(kExact));
    CHECK(c.redundancy == Approx(0.0).margin(kExact));
    CHECK(c.absolute.max == Approx(0.0).margin(kExact));
    CHECK(c.relative.count > 0);
    CHECK(c.relative.max == Approx(0.0).margin(kExact));
  }
}

TEST_CASE("a map shifted by 0.1 m has 0.1 m absolute and zero relative error", "[eval][map]") {
  VectorMap map = truthMap();
  for (auto& i : map.instances)
    for (auto& p : i.points) p.y() += 0.1;
  const auto m = evaluateMap(map, truthMap(), MapEvalParams{});
  const auto& lanes = get(m, CrowdClass::kLaneLine);
  CHECK(lanes.by_length);
  CHECK(lanes.absolute.mean == Approx(0.1).margin(kExact));
  CHECK(lanes.absolute.rms == Approx(0.1).margin(kExact));
  CHECK(lanes.absolute.p3sigma == Approx(0.1).margin(kExact));
  CHECK(lanes.relative.mean == Approx(0.0).margin(kExact));
  CHECK(lanes.completeness == Approx(1.0).margin(kExact));
  CHECK(lanes.redundancy == Approx(0.0).margin(kExact));
  CHECK(lanes.truth_length == Approx(300.0).margin(kExact));
  const auto& poles = get(m, CrowdClass::kPole);
  CHECK(!poles.by_length);
  CHECK(poles.absolute.mean == Approx(0.1).margin(kExact));
  CHECK(poles.relative.mean == Approx(0.0).margin(kExact));
  CHECK(poles.completeness == Approx(1.0).margin(kExact));
}

TEST_CASE("one line moved sideways changes every lane width by its offset", "[eval][map]") {
  VectorMap map = truthMap();
  for (auto& p : map.instances[1].points) p.y() += 0.1;  // the middle line
  for (auto& p : map.instances[5].points) p.x() += 0.3;  // pole at x = 50 -> 50.3
  const auto m = evaluateMap(map, truthMap(), MapEvalParams{});
  const auto& lanes = get(m, CrowdClass::kLaneLine);
  CHECK(lanes.relative.mean == Approx(0.1).margin(kExact));  // widths 3.6 / 3.4 vs 3.5
  CHECK(lanes.relative.max == Approx(0.1).margin(kExact));
  CHECK(lanes.absolute.mean == Approx(0.1 / 3.0).margin(kExact));  // one line of three
  // poles: nearest truth neighbours 0-20, 20-0, 50-20: only the last changes (30 -> 30.3)
  const auto& poles = get(m, CrowdClass::kPole);
  CHECK(poles.relative.count == 3);
  CHECK(poles.relative.mean == Approx(0.1).margin(kExact));
  CHECK(poles.absolute.mean == Approx(0.1).margin(kExact));
  CHECK(poles.absolute.max == Approx(0.3).margin(kExact));
}

TEST_CASE("a missing and a duplicated instance give exact completeness and redundancy",
          "[eval][map]") {
  VectorMap map = truthMap();
  MapInstance dup_line = map.instances[0];
  dup_line.id = 100;
  for (auto& p : dup_line.points) p.y() += 0.05;
  MapInstance dup_pole = map.instances[3];
  dup_pole.id = 101;
  dup_pole.points[0].x() += 0.2;
  // drop line y = 7 and pole x = 50; add the duplicates
  map.instances = {map.instances[0], map.instances[1], dup_line,
                   map.instances[3], map.instances[4], dup_pole};
  const auto m = evaluateMap(map, truthMap(), MapEvalParams{});
  const auto& lanes = get(m, CrowdClass::kLaneLine);
  CHECK(lanes.completeness == Approx(2.0 / 3.0).margin(kExact));  // 200 of 300 m
  CHECK(lanes.redundancy == Approx(1.0 / 3.0).margin(kExact));    // 100 of 300 m of map
  CHECK(lanes.matched_truth == 2);
  const auto& poles = get(m, CrowdClass::kPole);
  CHECK(poles.truth_count == 3);
  CHECK(poles.map_count == 3);
  CHECK(poles.matched_truth == 2);
  CHECK(poles.completeness == Approx(2.0 / 3.0).margin(kExact));
  CHECK(poles.redundancy == Approx(1.0 / 3.0).margin(kExact));
  CHECK(poles.absolute.max == Approx(0.0).margin(kExact));  // the exact pole wins the match
}

TEST_CASE("a false line far from the truth is redundant and unmatched", "[eval][map]") {
  VectorMap map = truthMap();
  map.instances.push_back(inst(200, CrowdClass::kLaneLine, line(30, 50)));
  const auto m = evaluateMap(map, truthMap(), MapEvalParams{});
  const auto& lanes = get(m, CrowdClass::kLaneLine);
  CHECK(lanes.completeness == Approx(1.0).margin(kExact));
  CHECK(lanes.redundancy == Approx(50.0 / 350.0).margin(kExact));
  CHECK(lanes.matched_map == 3);
}

TEST_CASE("maps with another origin are converted to the truth's ENU", "[eval][map]") {
  VectorMap truth = truthMap();
  VectorMap map = truthMap();
  const geo::EnuConverter a(truth.origin);
  map.origin = {49.0005, 8.4004, 111.0};
  const geo::EnuConverter b(map.origin);
  for (auto& i : map.instances)
    for (auto& p : i.points) p = b.toEnu(a.toWgs84(p));
  constexpr double kConversion = 1e-6;  // m, ENU round trip
  const auto m = evaluateMap(map, truth, MapEvalParams{});
  for (const auto& c : m.classes) {
    CHECK(c.completeness == Approx(1.0).margin(kExact));
    CHECK(c.absolute.max < kConversion);
  }
}

TEST_CASE("coverage keeps what is beside or ahead of a drive, not what lies behind its start",
          "[eval][map]") {
  // A drive along +x from x = 0 to x = 100 (poses every 1 m, heading east), radius 12 m.
  const std::vector<Pose3> poses = driveAlongX();
  VectorMap t =
      mapOf({inst(1, CrowdClass::kLaneLine, line(3.0, 160.0, -30.0)),
             inst(2, CrowdClass::kStopLine, {{-5, -2, 0}, {-5, 2, 0}}),    // behind the start
             inst(3, CrowdClass::kStopLine, {{105, -2, 0}, {105, 2, 0}}),  // ahead of the end
             inst(4, CrowdClass::kPole, {{50, 11, 0}}, 6),                 // beside, in range
             inst(5, CrowdClass::kPole, {{50, 13, 0}}, 6)});               // beside, too far
  const VectorMap c = clipToCoverage(t, poses, CoverageWedge{12.0, 12.0, 90.0, 0.0});
  std::vector<int64_t> ids;
  double lane_length = 0;
  for (const auto& m : c.instances) {
    ids.push_back(m.id);
    if (m.cls == CrowdClass::kLaneLine) {
      lane_length += polylineLength(m.points);
      CHECK(m.points.front().x() == Approx(0.0).margin(0.5));  // cut at the start's normal
    }
  }
  CHECK(std::count(ids.begin(), ids.end(), 2) == 0);
  CHECK(std::count(ids.begin(), ids.end(), 3) == 1);
  CHECK(std::count(ids.begin(), ids.end(), 4) == 1);
  CHECK(std::count(ids.begin(), ids.end(), 5) == 0);
  // ahead of the end the line stays covered out to sqrt(12^2 - 3^2) = 11.6 m
  CHECK(lane_length == Approx(100.0 + std::sqrt(12.0 * 12.0 - 9.0)).margin(0.6));
}

TEST_CASE("the coverage wedge follows the camera's field of view and reach", "[eval][map]") {
  // One pose at the origin heading north (body x = ENU y); wedge 22 m ahead, 12 m wide, 31 deg.
  const Pose3 pose(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  const CoverageWedge wedge{12.0, 22.0, 31.0, 0.0};  // tan 31 deg = 0.601, apex at the body
  auto seen = [&](double ahead, double left) {
    VectorMap t;
    t.instances = {inst(1, CrowdClass::kPole, {{-left, ahead, 0}}, 6)};
    return clipToCoverage(t, {pose}, wedge).instances.size() == 1;
  };
  CHECK(seen(10, 5));        // 5 <= 10 tan 31
  CHECK(seen(10, -5));       // both sides
  CHECK_FALSE(seen(5, 5));   // beside the car, outside the image
  CHECK_FALSE(seen(-1, 0));  // behind
  CHECK(seen(21.5, 0));
  CHECK_FALSE(seen(22.5, 0));  // beyond the reach
  CHECK(seen(20.5, 11.9));
  CHECK_FALSE(seen(21, 12.5));  // wider than the lateral limit
}

TEST_CASE("the coverage wedge opens at the camera, not at the body origin", "[eval][map]") {
  // The simulated camera sits 1.8 m ahead of the body origin (sim::CameraParams::x): its field of
  // view at 10 m ahead of the body reaches (10 - 1.8) tan 31 deg = 4.9 m to the side, not 6.0 m.
  // With the apex at the body origin the truth counted the ends of crossing roads' stop lines
  // the camera never had in its image (0.3-0.5 m visible, 1.3-1.6 m scored) as missed.
  const Pose3 pose = Pose3::Identity();
  const CoverageWedge wedge{12.0, 22.0, 31.0, CoverageWedge{}.apex_x};  // the default apex
  REQUIRE(wedge.apex_x == Approx(1.8));
  auto seen = [&](double ahead, double left) {
    VectorMap t;
    t.instances = {inst(1, CrowdClass::kPole, {{ahead, left, 0}}, 6)};
    return clipToCoverage(t, {pose}, wedge).instances.size() == 1;
  };
  CHECK(seen(10, 4.8));
  CHECK_FALSE(seen(10, 5.0));
  CHECK_FALSE(seen(1.5, 0));  // behind the camera
  CHECK(seen(2.0, 0));
}

TEST_CASE("map elements of true elements outside the scored scope count neither way",
          "[eval][map]") {
  // A drive along +x from x = 0 to x = 100: the scored truth is what the clip keeps; the map
  // also holds elements of what it left out (a pole behind the start, the line's part behind the
  // start) and one false pole.
  const std::vector<Pose3> poses = driveAlongX();
  VectorMap t = mapOf({inst(1, CrowdClass::kLaneLine, line(3.0, 140.0, -40.0)),
                       inst(2, CrowdClass::kPole, {{50, -3, 0}}, 6),
                       inst(3, CrowdClass::kPole, {{-20, -3, 0}}, 6)});  // behind the start
  VectorMap outside;
  const VectorMap scored = clipToCoverage(t, poses, CoverageWedge{12.0, 12.0, 90.0, 0.0}, &outside);
  REQUIRE(scored.instances.size() == 2);
  double out_length = 0;
  int out_poles = 0;
  for (const auto& m : outside.instances) {
    if (m.cls == CrowdClass::kLaneLine) out_length += polylineLength(m.points);
    if (m.cls == CrowdClass::kPole) ++out_poles;
  }
  CHECK(out_poles == 1);
  CHECK(out_length == Approx(40.0).margin(0.6));  // x in [-40, 0], up to the cut

  VectorMap map;
  map.origin = t.origin;
  std::vector<Vec3> map_lane;
  for (int x = -40; x <= 100; x += 10) map_lane.push_back({double(x), 3.1, 0.0});
  map.instances = {inst(1, CrowdClass::kLaneLine, map_lane),
                   inst(2, CrowdClass::kPole, {{50.2, -3, 0}}, 6),
                   inst(3, CrowdClass::kPole, {{-20.2, -3, 0}}, 6),  // a true pole, out of scope
                   inst(4, CrowdClass::kPole, {{70, -8, 0}}, 6)};    // false
  const MapEvalParams p;
  const auto with = evaluateMap(map, scored, p, &outside);
  const auto& lane_with = get(with, CrowdClass::kLaneLine);
  CHECK(lane_with.completeness == Approx(1.0).margin(kExact));
  CHECK(lane_with.map_length == Approx(100.0).margin(0.6));
  CHECK(lane_with.redundancy == Approx(0.0).margin(0.01));
  const auto& pole_with = get(with, CrowdClass::kPole);
  CHECK(pole_with.map_count == 2);
  CHECK(pole_with.redundancy == Approx(0.5).margin(kExact));  // the false pole only
  // Without the unscored truth both out-of-scope elements count as redundant.
  const auto without = evaluateMap(map, scored, p);
  CHECK(get(without, CrowdClass::kLaneLine).redundancy == Approx(40.0 / 140.0).margin(0.01));
  CHECK(get(without, CrowdClass::kPole).redundancy == Approx(2.0 / 3.0).margin(kExact));
}

TEST_CASE("a stop line mapped in part matches along its segment with its offset across it",
          "[eval][map]") {
  // truth: two stop lines across the road (x = 30 and x = 60, y from 0 to 3.5)
  VectorMap truth = mapOf({inst(1, CrowdClass::kStopLine, {{30, 0, 0}, {30, 3.5, 0}}),
                           inst(2, CrowdClass::kStopLine, {{60, 0, 0}, {60, 3.5, 0}})});
  // map: the first seen only from y = 2 to 3.5 (centre 1.0 m from the true centre, beyond
  // nothing) and 0.1 m too far along x; the second whole, 0.2 m short
  VectorMap map = truth;
  map.instances[0].points = {{30.1, 2.0, 0}, {30.1, 3.5, 0}};
  map.instances[1].points = {{59.8, 0, 0}, {59.8, 3.5, 0}};
  MapEvalParams p;
  p.discrete_tolerance = 0.5;  // the partial line's centre is 1.0 m from the true centre
  const MapMetrics metrics = evaluateMap(map, truth, p);  // get() refers into it
  const ClassMetrics& m = get(metrics, CrowdClass::kStopLine);
  CHECK(m.completeness == Approx(1.0));
  CHECK(m.redundancy == Approx(0.0));
  // the partial one by its 0.1 m across the line, the whole one by its centre (0.2 m)
  CHECK(m.absolute.mean == Approx(0.15).margin(kExact));
  // relative: true centres 30 m apart, placed at x = 30.1 (partial: the true centre moved by
  // its offset across) and 59.8 (its centre) -> 29.7 m
  CHECK(m.relative.mean == Approx(0.3).margin(kExact));
  // a pole (a point element) still matches by centre distance only
  VectorMap pole_truth = truthMap(), pole_map = truthMap();
  pole_map.instances[3].points = {{0.6, -3, 0}};
  const MapMetrics pole_metrics = evaluateMap(pole_map, pole_truth, p);
  const ClassMetrics& pm = get(pole_metrics, CrowdClass::kPole);
  CHECK(pm.completeness == Approx(2.0 / 3.0));
}

TEST_CASE("a stop line's centre lies along its length, whatever its vertices", "[eval][map]") {
  // A stitched stop line keeps the vertex where its two tiles' pieces were joined (here 1 m
  // from one end of a 7 m line); its errors must equal those of the same segment as 2 points.
  VectorMap truth = mapOf({inst(1, CrowdClass::kStopLine, {{30, 0, 0}, {30, 7, 0}}),
                           inst(2, CrowdClass::kStopLine, {{60, 0, 0}, {60, 7, 0}})});
  VectorMap segment = truth, joined = truth;
  segment.instances[0].points = {{30.2, 0, 0}, {30.2, 7, 0}};
  joined.instances[0].points = {{30.2, 0, 0}, {30.2, 1, 0}, {30.2, 7, 0}};
  MapEvalParams p;
  const MapMetrics ma = evaluateMap(segment, truth, p), mb = evaluateMap(joined, truth, p);
  const ClassMetrics& a = get(ma, CrowdClass::kStopLine);
  const ClassMetrics& b = get(mb, CrowdClass::kStopLine);
  CHECK(b.completeness == Approx(1.0));
  CHECK(b.absolute.mean == Approx(a.absolute.mean).margin(kExact));
  CHECK(b.absolute.mean == Approx(0.1).margin(kExact));  // (0.2 + 0) / 2
  CHECK(b.relative.mean == Approx(a.relative.mean).margin(kExact));
}

TEST_CASE("completeness over the true elements enough drives observed", "[eval][map]") {
  // Issue 36: poles 4 and 5 observed by three simulated drives, pole 6 by one; the map lacks
  // pole 6. Completeness 2 / 3; over what >= observedMinDrives() (3) drives saw, 2 / 2.
  REQUIRE(observedMinDrives() == 3);
  const VectorMap truth = truthMap();
  VectorMap map = truth;
  map.instances.pop_back();  // pole 6
  const auto dir = mapfuse::test::tempDir("observed");
  std::vector<std::string> files;
  for (int d = 0; d < 3; ++d) {
    Lsm lsm;
    lsm.drive_id = "drive" + std::to_string(d);
    lsm.vehicle_id = "veh";
    lsm.frame = LsmFrame::kEnu;
    lsm.origin = truth.origin;
    Keyframe kf;
    lsm.keyframes.push_back(kf);
    for (int64_t id : {4, 5, 6}) {
      if (id == 6 && d > 0) continue;  // one drive saw pole 6
      const MapInstance& t = truth.instances[std::size_t(id - 1)];
      Element e;
      e.id = id;
      e.cls = CrowdClass::kPole;
      e.anchor = 0;
      e.truth_id = id;
      e.points_body = t.points;
      e.covariances.assign(t.points.size(), Eigen::Matrix3d::Identity() * 1e-4);
      lsm.elements.push_back(e);
    }
    files.push_back((dir / (lsm.drive_id + ".lsm.cbor")).string());
    io::writeLsm(files.back(), lsm);
  }
  ScoredTruth scored;
  scored.scored = truth;
  scored.unscored = mapOf({});
  const MapMetrics m = scoreMap(map, scored, observedTruth(scored, files), MapEvalParams{});
  const ClassMetrics& pole = get(m, CrowdClass::kPole);
  CHECK(pole.completeness == Approx(2.0 / 3.0).margin(kExact));
  CHECK(pole.truth_observed == 2);
  CHECK(pole.completeness_observed == Approx(1.0).margin(kExact));
  CHECK(get(m, CrowdClass::kLaneLine).completeness_observed < 0);  // by length: not computed
}
