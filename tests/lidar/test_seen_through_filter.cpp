// Free-space (seen-through) test: hand-made maps and scans whose verdicts are known — a voxel the
// rays pass goes, a voxel the rays stop at stays, occluded voxels and voxels without returns
// around them stay, the thresholds on scans and ratio, the wider window of thin classes, and
// the settings' validation; and per-scan labels of the points in removed trace voxels.
#include <catch2/catch.hpp>
#include <cmath>

#include "mapfuse/core/error.hpp"
#include "mapfuse/lidar/map_export.hpp"
#include "mapfuse/lidar/seen_through_filter.hpp"

using namespace mapfuse;
using lidar::SeenThroughFilter;
using lidar::SeenThroughSettings;
using lidar::SemanticVoxelMap;

namespace {

constexpr double kVoxel = 0.05;

/// Inserts a voxel at p labelled `cls` (fused with a confident measurement); returns its index.
std::size_t addVoxel(SemanticVoxelMap& map, const Eigen::Vector3d& p, LidarClass cls) {
  const std::size_t i = map.findOrInsert(lidar::packKey(map.coordOf(p)));
  lidar::ClassDistribution m;
  m.fill(0.01f);
  m[static_cast<int>(cls)] = 0.93f;
  map.fuse(i, m);
  return i;
}

/// A return along the direction of `target` (map frame) as seen from a sensor at `sensor`
/// (identity rotation), at `range` metres.
Eigen::Vector3f returnToward(const Eigen::Vector3d& sensor, const Eigen::Vector3d& target,
                             double range) {
  return ((target - sensor).normalized() * range).cast<float>();
}

Pose3 at(const Eigen::Vector3d& t) {
  Pose3 T = Pose3::Identity();
  T.translation() = t;
  return T;
}

}  // namespace

TEST_CASE("seen-through: voxels passed by the rays go, voxels stopping them stay",
          "[lidar][refinement]") {
  SemanticVoxelMap map(kVoxel);
  const Eigen::Vector3d trace(10.025, 0.025, 0.525), parked(10.025, 5.025, 0.525),
      hidden(20.025, 0.025, 0.525), dark(10.025, -5.025, 0.525);
  const std::size_t i_trace = addVoxel(map, trace, LidarClass::kVehicle);
  const std::size_t i_parked = addVoxel(map, parked, LidarClass::kVehicle);
  const std::size_t i_hidden = addVoxel(map, hidden, LidarClass::kVehicle);
  const std::size_t i_dark = addVoxel(map, dark, LidarClass::kBuilding);
  SeenThroughSettings s;
  SeenThroughFilter f(map, s);
  for (const double x : {0.0, 1.0, 2.0}) {  // three scans along the road
    const Eigen::Vector3d sensor(x, 0.0, 0.0);
    std::vector<Eigen::Vector3f> scan;
    const double r_trace = (trace - sensor).norm(), r_parked = (parked - sensor).norm();
    scan.push_back(returnToward(sensor, trace, r_trace + 5.0));    // through the trace to a wall
    scan.push_back(returnToward(sensor, parked, r_parked + 0.1));  // stopped by the parked car
    // `hidden` lies beyond the wall behind the trace (occluded where it shares the wall's pixel,
    // unseen otherwise); `dark` has no return anywhere near its direction.
    f.addScan(scan, at(sensor));
  }
  lidar::SeenThroughStats st;
  const auto keep = f.keepMask(&st);
  REQUIRE(keep.size() == map.size());
  CHECK(keep[i_trace] == 0);
  CHECK(keep[i_parked] == 1);
  CHECK(keep[i_hidden] == 1);
  CHECK(keep[i_dark] == 1);
  CHECK(st.tested_voxels == map.size());
  CHECK(st.scans == 3);
  CHECK(st.removed_voxels == 1);
}

TEST_CASE("seen-through: min_seen_through and min_free_ratio decide", "[lidar][refinement]") {
  SemanticVoxelMap map(kVoxel);
  const Eigen::Vector3d v(8.025, 2.025, 0.325);
  const std::size_t i = addVoxel(map, v, LidarClass::kVehicle);
  const Eigen::Vector3d o = Eigen::Vector3d::Zero();
  const double r = (v - o).norm();
  auto run = [&](int through, int hit, int min_scans, double ratio) {
    SeenThroughSettings s;
    s.min_seen_through = min_scans;
    s.vehicle_vote_radius = 0.0;  // this voxel's own verdict
    s.min_free_ratio = ratio;
    SeenThroughFilter f(map, s);
    for (int k = 0; k < through; ++k) f.addScan({returnToward(o, v, r + 3.0)}, at(o));
    for (int k = 0; k < hit; ++k) f.addScan({returnToward(o, v, r)}, at(o));
    return f.keepMask(nullptr)[i];
  };
  CHECK(run(1, 0, 2, 0.5) == 1);  // seen through once: not enough
  CHECK(run(2, 0, 2, 0.5) == 0);
  CHECK(run(2, 3, 2, 0.5) == 1);  // 2 of 5 scans saw through: below the ratio (a car that
                                  // stood still for a while, then left, stays)
  CHECK(run(3, 3, 2, 0.5) == 0);
  CHECK(run(2, 3, 2, 0.4) == 0);
}

TEST_CASE("seen-through: vehicle voxels go by their neighbourhood's vote", "[lidar][refinement]") {
  // A 5 x 5 block of vehicle voxels 10 m ahead (columns 0.1 m apart, so that each voxel has its
  // own range-image pixel), 3 scans from the origin. `through(i)` says which voxels the rays pass.
  const Eigen::Vector3d o = Eigen::Vector3d::Zero();
  auto run = [&](auto through, double vote_radius) {
    SemanticVoxelMap map(kVoxel);
    std::vector<std::size_t> ids;
    std::vector<Eigen::Vector3d> at_;
    for (int iy = 0; iy < 5; ++iy)
      for (int iz = 0; iz < 5; ++iz) {
        const Eigen::Vector3d p(10.025, 0.025 + 0.1 * iy, -1.675 + 0.25 * iz);
        ids.push_back(addVoxel(map, p, LidarClass::kVehicle));
        at_.push_back(p);
      }
    SeenThroughSettings s;
    s.vehicle_vote_radius = vote_radius;
    SeenThroughFilter f(map, s);
    for (int scan = 0; scan < 3; ++scan) {
      std::vector<Eigen::Vector3f> pts;
      for (std::size_t i = 0; i < at_.size(); ++i) {
        const double r = (at_[i] - o).norm();
        pts.push_back(returnToward(o, at_[i], through(i) ? r + 3.0 : r + 0.1));
      }
      f.addScan(pts, at(o));
    }
    const auto keep = f.keepMask(nullptr);
    int kept = 0;
    for (const std::size_t i : ids) kept += keep[i];
    return kept;
  };
  // A trace: every voxel seen through except its lowest layer, where the ray meets the road
  // just behind it (within the margin).
  auto trace = [](std::size_t i) { return i % 5 != 0; };
  CHECK(run(trace, 0.0) == 5);  // alone, the bottom layer stays
  CHECK(run(trace, 0.5) == 0);  // with the vote, the whole trace goes
  // A parked car: two edge voxels passed by grazing rays.
  auto parked = [](std::size_t i) { return i == 4 || i == 9; };
  CHECK(run(parked, 0.0) == 23);
  CHECK(run(parked, 0.5) == 25);
}

TEST_CASE("seen-through: thin classes use the wider window", "[lidar][refinement]") {
  // A pole voxel whose own pixel sees through, but a neighbouring pixel returns from the pole:
  // with window_thin = 1 the pole stays; a vehicle voxel in the same place (window 0) goes.
  const Eigen::Vector3d v(12.025, 0.025, 0.525);
  const Eigen::Vector3d o = Eigen::Vector3d::Zero();
  const double r = (v - o).norm();
  const double az_step = 1.5 * 0.2 * 3.14159265358979323846 / 180.0;  // next image column
  const Eigen::Vector3d beside(r * std::cos(az_step), r * std::sin(az_step), v.z());
  for (const auto cls : {LidarClass::kPole, LidarClass::kVehicle}) {
    SemanticVoxelMap map(kVoxel);
    const std::size_t i = addVoxel(map, v, cls);
    SeenThroughFilter f(map, SeenThroughSettings{});
    for (int k = 0; k < 3; ++k)
      f.addScan({returnToward(o, v, r + 4.0), returnToward(o, beside, beside.norm())}, at(o));
    CHECK(f.keepMask(nullptr)[i] == (cls == LidarClass::kPole ? 1 : 0));
  }
}

TEST_CASE("seen-through: settings are validated", "[lidar][refinement]") {
  SemanticVoxelMap map(kVoxel);
  SeenThroughSettings s;
  s.margin = 0.0;
  CHECK_THROWS_AS(SeenThroughFilter(map, s), InputError);
  s = SeenThroughSettings{};
  s.azimuth_resolution_deg = -1.0;
  CHECK_THROWS_AS(SeenThroughFilter(map, s), InputError);
  s = SeenThroughSettings{};
  s.window = -1;
  CHECK_THROWS_AS(SeenThroughFilter(map, s), InputError);
  s = SeenThroughSettings{};
  CHECK_THROWS_AS(SeenThroughFilter(map, s, lidar::SensorReach{20.0, 20.0}), InputError);
  s = SeenThroughSettings{};
  s.vehicle_vote_radius = -0.1;
  CHECK_THROWS_AS(SeenThroughFilter(map, s), InputError);
  s = SeenThroughSettings{};
  s.vehicle_vote_share = 0.0;
  CHECK_THROWS_AS(SeenThroughFilter(map, s), InputError);
  s = SeenThroughSettings{};
  SeenThroughFilter empty(map, s);
  empty.addScan({Eigen::Vector3f(5, 0, 0)}, Pose3::Identity());
  CHECK(empty.keepMask(nullptr).empty());
}

TEST_CASE("scan labels: points in voxels refinement removed keep their labels",
          "[lidar][refinement]") {
  SemanticVoxelMap map(kVoxel);
  const Eigen::Vector3d car(6.025, 0.025, 0.525), road(6.025, 2.025, -1.725),
      wall(6.025, 4.025, 0.525), parked(6.025, -4.025, 0.525);
  addVoxel(map, car, LidarClass::kVehicle);
  addVoxel(map, road, LidarClass::kRoad);
  addVoxel(map, wall, LidarClass::kBuilding);
  addVoxel(map, parked, LidarClass::kVehicle);
  // Refinement removed the car and the wall voxel as traces and the parked-car voxel as an
  // isolated voxel (K-nearest filter); the road stays.
  lidar::RemovedVoxelLabels removed;
  std::vector<uint8_t> keep(map.size(), 1);
  for (std::size_t i = 0; i < map.size(); ++i) {
    const auto cls = static_cast<LidarClass>(map.voxels()[i].label);
    if (cls == LidarClass::kRoad) continue;
    const bool isolated = map.center(map.voxels()[i].key).y() < 0.0;
    removed[map.voxels()[i].key] = {map.voxels()[i].label, !isolated};
    keep[i] = 0;
  }
  map.filter(keep);
  const std::vector<Eigen::Vector3f> scan = {car.cast<float>(), road.cast<float>(),
                                             wall.cast<float>(), parked.cast<float>(),
                                             Eigen::Vector3f(30, 0, 0)};
  const auto plain = lidar::scanLabels(map, Pose3::Identity(), scan);
  CHECK(plain == std::vector<uint32_t>{0, semanticKittiId(LidarClass::kRoad), 0, 0, 0});
  const auto with = lidar::scanLabels(map, Pose3::Identity(), scan, &removed);
  CHECK(with == std::vector<uint32_t>{252, semanticKittiId(LidarClass::kRoad),
                                      semanticKittiId(LidarClass::kBuilding),
                                      semanticKittiId(LidarClass::kVehicle), 0});
}
