#include <catch2/catch.hpp>
#include <random>

#include "mapfuse/core/error.hpp"
#include "mapfuse/tiling/split.hpp"
#include "mapfuse/tiling/stitch.hpp"

using namespace mapfuse;
using namespace mapfuse::tiling;

namespace {
constexpr double kExact = 1e-9;
constexpr double kLengthRelTol = 0.01;  // stitched line length vs truth
constexpr double kTileNoise = 0.05;     // m: tiles aligned independently disagree this much

VectorMap truthMap() {
  VectorMap m;
  m.origin = {49.0, 8.4, 110.0};
  MapInstance lane;
  lane.id = 1;
  lane.cls = CrowdClass::kLaneLine;
  lane.attributes = {LineStyle::kSolid, LineColor::kWhite};
  for (double s = -150; s <= 150; s += 1.0)
    lane.points.emplace_back(s, 20.0 * std::sin(s / 60.0) + 3.0, 0.0);
  lane.support = {10, 100};
  m.instances.push_back(lane);
  int64_t id = 2;
  for (double x : {-99.0, -51.0, -1.0, 0.5, 49.0, 99.5}) {
    MapInstance pole;
    pole.id = id++;
    pole.cls = CrowdClass::kPole;
    pole.points = {{x, 1.0 - x / 50.0, 0.0}};
    pole.height = 5;
    m.instances.push_back(pole);
  }
  return m;
}

// What aggregate would produce in one tile: everything within the margin rectangle, shifted a bit.
VectorMap tileView(const VectorMap& truth, const TileGrid& grid, const TileKey& key, double shift) {
  VectorMap m;
  m.origin = truth.origin;
  const Rect r = grid.withMargin(key);
  for (const auto& inst : truth.instances) {
    if (geometryKind(inst.cls) == GeometryKind::kLine) {
      for (const auto& piece : clipPolyline(inst.points, r)) {
        MapInstance part = inst;
        part.points = piece.points;
        for (auto& p : part.points) p.x() += shift;
        m.instances.push_back(part);
      }
    } else if (r.contains(inst.points[0].x(), inst.points[0].y())) {
      MapInstance copy = inst;
      copy.points[0].x() += shift;
      m.instances.push_back(copy);
    }
  }
  return m;
}
}  // namespace

TEST_CASE("tile cores partition the plane and margins overlap", "[tiling]") {
  const TileGrid grid(100.0, 10.0);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-500, 500);
  for (int i = 0; i < 1000; ++i) {
    const double x = u(rng), y = u(rng);
    int owners = 0;
    for (const auto& k : grid.tilesTouching(x, y)) owners += grid.core(k).ownsPoint(x, y);
    REQUIRE(owners == 1);
  }
  CHECK(grid.tilesTouching(100.0, 100.0).size() == 4);  // a corner
  CHECK(grid.tilesTouching(50.0, 50.0).size() == 1);    // a tile's middle
  CHECK(grid.keyOf(-0.1, 0.0) == TileKey{-1, 0});
  CHECK(TileKey{-3, 2}.name() == "tile_m3_2");
  CHECK_THROWS_AS(TileGrid(100.0, 60.0), ConfigError);
}

TEST_CASE("polylines are clipped to a rectangle with their cut ends marked", "[tiling]") {
  const Rect r{0, 0, 20, 10};
  const auto through = clipPolyline({{-10, 5, 0}, {30, 5, 0}}, r);
  REQUIRE(through.size() == 1);
  CHECK((through[0].points.front() - Eigen::Vector3d(0, 5, 0)).norm() < kExact);
  CHECK((through[0].points.back() - Eigen::Vector3d(20, 5, 0)).norm() < kExact);
  CHECK(through[0].start_cut);
  CHECK(through[0].end_cut);
  const auto inside_start = clipPolyline({{5, 5, 0}, {10, 5, 0}, {25, 5, 0}}, r);
  REQUIRE(inside_start.size() == 1);
  CHECK_FALSE(inside_start[0].start_cut);
  CHECK(inside_start[0].end_cut);
  CHECK(inside_start[0].points.size() == 3);
  const auto in_and_out = clipPolyline({{5, 5, 0}, {5, 15, 0}, {15, 15, 0}, {15, 5, 0}}, r);
  CHECK(in_and_out.size() == 2);
  CHECK(clipPolyline({{-5, -5, 0}, {-1, -1, 0}}, r).empty());
}

TEST_CASE("stitching 2x2 tile maps gives back each instance once and the line whole", "[tiling]") {
  const TileGrid grid(100.0, 20.0);
  const VectorMap truth = truthMap();
  std::vector<std::pair<TileKey, VectorMap>> tiles;
  double shift = -kTileNoise;
  for (int64_t ix = -2; ix <= 1; ++ix)
    for (int64_t iy = -1; iy <= 0; ++iy) {
      tiles.emplace_back(TileKey{ix, iy}, tileView(truth, grid, {ix, iy}, shift));
      shift = -shift;
    }
  StitchParams params;
  StitchReport report;
  const VectorMap out = stitchTiles(tiles, grid, params, report);

  int lanes = 0, poles = 0;
  for (const auto& inst : out.instances) {
    if (inst.cls == CrowdClass::kLaneLine) {
      ++lanes;
      CHECK(polylineLength(inst.points) ==
            Approx(polylineLength(truth.instances[0].points)).epsilon(kLengthRelTol));
      CHECK(inst.attributes == truth.instances[0].attributes);
    } else {
      ++poles;
    }
  }
  CHECK(lanes == 1);  // no gap: one line across every border
  CHECK(poles == 6);  // no duplicate from the overlapping margins, none missing
  CHECK(report.joins >= 3);
  for (std::size_t i = 0; i < out.instances.size(); ++i)
    CHECK(out.instances[i].id == int64_t(i + 1));
}

TEST_CASE("a stop line across a tile border stays one segment from the tile owning its centre",
          "[tiling]") {
  const TileGrid grid(100.0, 20.0);
  // Both tiles hold the whole stop line (margins); the east tile saw it 0.1 m further north.
  auto stopLine = [](double dy) {
    VectorMap m;
    m.origin = {49.0, 8.4, 110.0};
    MapInstance s;
    s.id = 1;
    s.cls = CrowdClass::kStopLine;
    s.points = {{97.0, 10.0 + dy, 0.0}, {104.0, 10.5 + dy, 0.0}};  // centre x = 100.5: east tile
    m.instances.push_back(s);
    return m;
  };
  StitchReport report;
  const VectorMap out = stitchTiles({{TileKey{0, 0}, stopLine(0.0)}, {TileKey{1, 0}, stopLine(0.1)}},
                                    grid, StitchParams{}, report);
  REQUIRE(out.instances.size() == 1);
  const auto& kept = out.instances[0].points;
  REQUIRE(kept.size() == 2);  // a segment, not two clipped pieces joined at the border
  CHECK((kept[0] - Eigen::Vector3d(97.0, 10.1, 0.0)).norm() < kExact);
  CHECK((kept[1] - Eigen::Vector3d(104.0, 10.6, 0.0)).norm() < kExact);
  CHECK(report.joins == 0);
}

TEST_CASE("stitching refuses maps with different origins", "[tiling]") {
  const TileGrid grid(100.0, 20.0);
  VectorMap a = truthMap(), b = truthMap();
  b.origin.lat += 0.01;
  StitchReport report;
  CHECK_THROWS_AS(
      stitchTiles({{TileKey{0, 0}, a}, {TileKey{1, 0}, b}}, grid, StitchParams{}, report),
      InputError);
}

TEST_CASE("splitting cuts drives into per-tile runs with their elements", "[tiling]") {
  Lsm lsm;
  lsm.drive_id = "d1";
  lsm.frame = LsmFrame::kEnu;
  lsm.origin = geo::GeoOrigin{49.0, 8.4, 110.0};
  // Out along y = 5 from x = 0 to 290, then back along y = 15 (the drive re-enters tiles).
  int id = 0;
  for (double x = 0; x <= 290; x += 10, ++id) {
    Keyframe k;
    k.id = id;
    k.stamp = id;
    k.T_frame_body.translation() = Eigen::Vector3d(x, 5, 0);
    lsm.keyframes.push_back(k);
  }
  for (double x = 290; x >= 0; x -= 10, ++id) {
    Keyframe k;
    k.id = id;
    k.stamp = id;
    k.T_frame_body.translation() = Eigen::Vector3d(x, 15, 0);
    lsm.keyframes.push_back(k);
  }
  Element e;
  e.id = 1;
  e.anchor = 3;  // x = 30: tile (0, 0) only
  e.points_body = {{1, 0, 0}, {2, 0, 0}};
  e.covariances = {Eigen::Matrix3d::Identity(), Eigen::Matrix3d::Identity()};
  lsm.elements.push_back(e);
  lsm.gps.push_back({3.0, {49.0, 8.4, 110.0}, 1.0, 2.0});

  const TileGrid grid(100.0, 10.0);
  const auto tiles = splitLsm(lsm, grid, 2);
  REQUIRE(tiles.count(TileKey{0, 0}));
  const auto& t00 = tiles.at(TileKey{0, 0});
  REQUIRE(t00.size() == 2);  // out and back
  CHECK(t00[0].drive_id == "d1.run0");
  CHECK(t00[0].elements.size() == 1);
  CHECK(t00[0].gps.size() == 1);
  CHECK(t00[1].elements.empty());
  // Every keyframe lands in each tile whose margin rectangle contains it.
  std::size_t total = 0;
  for (const auto& [key, runs] : tiles)
    for (const auto& r : runs) {
      for (const auto& k : r.keyframes)
        CHECK(grid.withMargin(key).contains(k.T_frame_body.translation().x(),
                                            k.T_frame_body.translation().y()));
      total += r.keyframes.size();
    }
  CHECK(total > lsm.keyframes.size());  // margins duplicate keyframes near borders

  Lsm odom = lsm;
  odom.frame = LsmFrame::kOdom;
  CHECK_THROWS_AS(splitLsm(odom, grid, 2), InputError);
}
