// Aggregation on geometry at the edge of what readers accept: bounded work and a clear error
// instead of an endless loop or an allocation of gigabytes (issue 19).
#include <catch2/catch.hpp>

#include "aggregate/lane_instantiation.hpp"
#include "mapfuse/aggregate/road_length.hpp"
#include "mapfuse/core/error.hpp"

using namespace mapfuse;
using namespace mapfuse::aggregate;
using Catch::Contains;

namespace {

Observation laneObservation(int drive, int64_t id, std::vector<Eigen::Vector3d> points) {
  Observation o;
  o.drive = drive;
  o.element_id = id;
  o.cls = CrowdClass::kLaneLine;
  o.points = std::move(points);
  return o;
}

}  // namespace

TEST_CASE("lane tiling refuses coordinates without a tile instead of looping",
          "[aggregate][bounds]") {
  // x = 1e308: `g += tile_size` no longer advanced and cutAtTiles looped forever.
  const std::vector<Observation> items = {laneObservation(0, 7, {{0, 0, 0}, {1e308, 0, 0}}),
                                          laneObservation(1, 8, {{0, 0.1, 0}, {20, 0.1, 0}})};
  CHECK_THROWS_WITH(instantiateLanes(items, {0, 1}, LaneInstantiationParams{}, 2),
                    Contains("no tile"));
}

TEST_CASE("lane tiling checks its piece budget before cutting", "[aggregate][bounds]") {
  // 200 observations each 9.9 km long cross ~2000 tiles of 10 m: 4e5 pieces, refused at once
  // (one element reaching x = 1e8 m made aggregate allocate 5.7 GB and die with bad_alloc).
  std::vector<Observation> items;
  std::vector<std::size_t> indices;
  for (int i = 0; i < 200; ++i) {
    items.push_back(laneObservation(i % 3, i, {{0, 3.5 * i, 0}, {7000, 7000 + 3.5 * i, 0}}));
    indices.push_back(std::size_t(i));
  }
  CHECK_THROWS_WITH(instantiateLanes(items, indices, LaneInstantiationParams{}, 3),
                    Contains("pieces") && Contains("crosses"));
  // One such observation among ordinary ones is within the budget and instantiated.
  std::vector<Observation> few(items.begin(), items.begin() + 1);
  for (int i = 0; i < 30; ++i)
    few.push_back(laneObservation(i % 3, 1000 + i, {{0, 50, 0}, {30, 50, 0}}));
  std::vector<std::size_t> all(few.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  const LaneInstantiation lanes = instantiateLanes(few, all, LaneInstantiationParams{}, 3);
  CHECK(lanes.stats.pieces >= 700);  // the diagonal passes tile corners: one piece a tile
}

TEST_CASE("road coverage skips a keyframe jump instead of sampling it every metre",
          "[aggregate][bounds]") {
  // A 1.4e7 m step was sampled every metre into a hash map: 2.4 GB.
  Lsm lsm;
  for (int i = 0; i < 4; ++i) {
    Keyframe k;
    k.id = i;
    k.stamp = i;
    k.T_frame_body.translation() = Eigen::Vector3d(10.0 * i, 0, 0);
    lsm.keyframes.push_back(k);
  }
  const RoadLengthSettings settings;  // the default road_tolerance, 10 m
  const double straight = coveredRoadKm({lsm}, settings);
  CHECK(straight == Approx(0.030).margin(1e-9));
  lsm.keyframes[2].T_frame_body.translation() = Eigen::Vector3d(1e7, -1e7, 0);
  CHECK(coveredRoadKm({lsm}, settings) == Approx(0.010).margin(1e-9));
}
