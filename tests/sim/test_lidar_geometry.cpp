// Ray casting geometry of the LiDAR simulator: primitives, ground, beam layout, scan size.
#include <catch2/catch.hpp>
#include <cmath>

#include "mapfuse/sim/lidar_scene_generator.hpp"
#include "mapfuse/sim/lidar_sensor.hpp"

using namespace mapfuse;
using namespace mapfuse::sim;

namespace {
constexpr double kGeomTol = 1e-9;  // m, analytic intersections
constexpr double kCurbTol = 1e-3;  // m, bisection of the curb face
constexpr double kDegTol = 1e-9;   // rad

Road straightRoad() {
  return Road(makeCentreline({200.0}, {}, {}, 1.0), RoadProfile{}, 12.0);
}
}  // namespace

TEST_CASE("lidar primitives: box, cylinder and ellipsoid entry distances") {
  const Eigen::Vector3d o(0, 0, 1), d(1, 0, 0);
  Primitive box;
  box.kind = Primitive::Kind::kBox;
  box.centre = {10, 0, 1};
  box.half = {1, 2, 3};
  CHECK(box.intersect(o, d, 0, 100) == Approx(9.0).margin(kGeomTol));
  box.yaw = M_PI / 4;  // along the ray the rotated 2 x 4 box reaches sqrt(2) * half.x
  CHECK(box.intersect(o, d, 0, 100) == Approx(10.0 - std::sqrt(2.0)).margin(kGeomTol));
  CHECK(box.intersect(o, d, 0, 5) < 0);  // beyond tmax
  Primitive cyl;
  cyl.kind = Primitive::Kind::kCylinder;
  cyl.centre = {20, 0, 2};
  cyl.half = {0.5, 0.5, 2};
  CHECK(cyl.intersect(o, d, 0, 100) == Approx(19.5).margin(kGeomTol));
  CHECK(cyl.intersect({0, 0, 5}, d, 0, 100) < 0);  // passes over the top
  Primitive ell;
  ell.kind = Primitive::Kind::kEllipsoid;
  ell.centre = {30, 0, 1};
  ell.half = {2, 1, 1};
  CHECK(ell.intersect(o, d, 0, 100) == Approx(28.0).margin(kGeomTol));
  ell.yaw = M_PI / 2;  // long axis across the ray: semi-axis 1 along x
  CHECK(ell.intersect(o, d, 0, 100) == Approx(29.0).margin(kGeomTol));
}

TEST_CASE("lidar ground: a beam meets the road plane at the range its elevation predicts") {
  const LidarScene scene(straightRoad(), {}, {});
  const double h = 1.73;
  for (double elev_deg : {-5.0, -10.0, -24.33}) {
    const double e = elev_deg * M_PI / 180.0;
    const Eigen::Vector3d o(50, -1.75, h), d(std::cos(e), 0, std::sin(e));
    const RayHit hit = scene.cast(o, d, 120.0, {});
    REQUIRE(hit.hit());
    CHECK(hit.t == Approx(h / std::sin(-e)).margin(kGeomTol));
    CHECK(hit.label.cls == LidarClass::kRoad);
  }
  // Sideways: the ray reaches the curb face at lateral -5 m, below the sidewalk height.
  const double e = -std::atan2(h - 0.05, 5.0 - 1.75);  // would hit z = 0 at lateral -5 - eps
  const Eigen::Vector3d o(50, -1.75, h), d(0, -std::cos(e), std::sin(e));
  const RayHit curb = scene.cast(o, d.normalized(), 120.0, {});
  REQUIRE(curb.hit());
  CHECK(curb.label.cls == LidarClass::kSidewalk);
  const Eigen::Vector3d p = o + curb.t * d.normalized();
  CHECK(p.y() == Approx(-5.0).margin(kCurbTol));
  CHECK(p.z() > 0.0);
  CHECK(p.z() < 0.15);
  // Farther out: the sidewalk top at curb height.
  const Eigen::Vector3d d2 = Eigen::Vector3d(0, -6.5 + 1.75, 0.15 - h).normalized();
  const RayHit side = scene.cast(o, d2, 120.0, {});
  CHECK(side.label.cls == LidarClass::kSidewalk);
  CHECK((o + side.t * d2).z() == Approx(0.15).margin(kGeomTol));
}

TEST_CASE("lidar ground: lane markings carry SemanticKITTI lane-marking 60 and count as road") {
  const Road road = straightRoad();
  RoadCoord c;
  c.near = true;
  c.s = 1.0;  // inside the first dash
  c.lateral = 0.0;
  CHECK(road.groundAt(c) == GroundKind::kLaneMarking);
  c.s = 4.0;  // in the gap
  CHECK(road.groundAt(c) == GroundKind::kRoad);
  CHECK(LidarScene::groundLabel(GroundKind::kLaneMarking).kitti_id == 60);
  CHECK(lidarClassFromSemanticKitti(60) == LidarClass::kRoad);
}

TEST_CASE("lidar scene: a wall in the grid is hit at its known range, nearest surface wins") {
  Primitive wall;
  wall.kind = Primitive::Kind::kBox;
  wall.centre = {60, 10, 5};
  wall.half = {0.5, 20, 5};
  wall.label = {LidarClass::kBuilding, 50, 0, 0.3f};
  Primitive pole = wall;
  pole.kind = Primitive::Kind::kCylinder;
  pole.centre = {55, 10, 3};
  pole.half = {0.1, 0.1, 3};
  pole.label = {LidarClass::kPole, 80, 0, 0.4f};
  const LidarScene scene(straightRoad(), {wall, pole}, {});
  const Eigen::Vector3d o(20, 8, 1.73), d(1, 0, 0);
  const RayHit hit = scene.cast(o, d, 120.0, {});
  CHECK(hit.label.cls == LidarClass::kBuilding);
  CHECK(hit.t == Approx(39.5).margin(kGeomTol));
  const RayHit at_pole = scene.cast({20, 10, 1.73}, d, 120.0, {});
  CHECK(at_pole.label.cls == LidarClass::kPole);
  CHECK(at_pole.t == Approx(34.9).margin(kGeomTol));
  CHECK(!scene.cast(o, d, 30.0, {}).hit());  // beyond the maximum range
}

TEST_CASE("lidar sensor: HDL-64E beam layout") {
  const LidarSensorParams p;
  const auto e = beamElevations(p);
  REQUIRE(e.size() == 64);
  const double deg = M_PI / 180.0;
  CHECK(e.front() == Approx(2.0 * deg).margin(kDegTol));
  CHECK(e[31] == Approx(-8.33 * deg).margin(kDegTol));
  CHECK(e[32] == Approx(-8.83 * deg).margin(kDegTol));
  CHECK(e.back() == Approx(-24.33 * deg).margin(kDegTol));
  for (std::size_t i = 1; i < e.size(); ++i) CHECK(e[i] < e[i - 1]);
  CHECK((e[0] - e[1]) / deg == Approx(10.33 / 31).margin(1e-9));   // ~1/3 deg upper block
  CHECK((e[32] - e[33]) / deg == Approx(15.5 / 31).margin(1e-9));  // 1/2 deg lower block
}

TEST_CASE("lidar sensor: a default street scan has ~120k labelled points and is reproducible") {
  StreetParams sp;
  const LidarScene scene = generateStreet(sp, 7);
  const Eigen::Vector2d xy = scene.road().pointAt(40.0, -1.75);
  const Pose3 T = poseFromXyzRpy(xy.x(), xy.y(), 1.73, 0, 0, scene.road().headingAt(40.0));
  const LidarSensorParams p;
  const LidarScan a = scanLidar(scene, T, 0.0, p, 99);
  CHECK(a.points.size() > 100000);
  CHECK(a.points.size() < 140000);
  REQUIRE(a.labels.size() == a.points.size());
  // Every point is labelled with a known class, and ranges obey the sensor limits.
  for (std::size_t i = 0; i < a.points.size(); i += 97) {
    CHECK(lidarClassFromSemanticKitti(a.labels[i] & 0xFFFF) != LidarClass::kUnlabeled);
    const double r = a.points[i].head<3>().norm();
    CHECK(r > p.min_range - 0.2);
    CHECK(r < p.max_range + 0.2);
  }
  const LidarScan b = scanLidar(scene, T, 0.0, p, 99);
  CHECK(a.points == b.points);
  CHECK(a.labels == b.labels);
  const LidarScan c = scanLidar(scene, T, 0.0, p, 100);
  CHECK(c.points != a.points);
}

TEST_CASE("lidar scene: moving cars advance along the road and are labelled 252 with instances") {
  StreetParams sp;
  const LidarScene scene = generateStreet(sp, 3);
  REQUIRE(scene.movers().size() == 6);
  const auto p0 = scene.dynamicAt(0.0), p1 = scene.dynamicAt(1.0);
  REQUIRE(!p0.empty());
  CHECK(p0[0].label.kitti_id == kSemanticKittiMovingCar);
  CHECK(p0[0].label.instance >= 1000);
  const double moved = (p1[0].centre - p0[0].centre).head<2>().norm();
  CHECK(moved == Approx(std::abs(scene.movers()[0].speed)).epsilon(0.05));
}
