#include <catch2/catch.hpp>

#include "mapfuse/cli/params.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/lsm_io.hpp"
#include "mapfuse/io/vector_map_io.hpp"
#include "mapfuse/stages/balance.hpp"
#include "mapfuse/stages/stitch.hpp"
#include "mapfuse/stages/tile.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;

namespace {
Lsm straightDrive(const std::string& id, double y) {
  Lsm lsm;
  lsm.drive_id = id;
  lsm.frame = LsmFrame::kEnu;
  lsm.origin = geo::GeoOrigin{49.0, 8.4, 110.0};
  for (int i = 0; i <= 60; ++i) {
    Keyframe k;
    k.id = i;
    k.stamp = i;
    k.T_frame_body.translation() = Eigen::Vector3d(-300.0 + 10.0 * i, y, 0);
    lsm.keyframes.push_back(k);
    Element e;
    e.id = i;
    e.anchor = i;
    e.points_body = {{0, 1.75, 0}, {5, 1.75, 0}};
    e.covariances = {Eigen::Matrix3d::Identity() * 0.01, Eigen::Matrix3d::Identity() * 0.01};
    lsm.elements.push_back(e);
  }
  return lsm;
}
}  // namespace

TEST_CASE("configs/tile.json, balance.json and stitch.json mirror the defaults",
          "[tiling][config]") {
  const std::filesystem::path configs = std::filesystem::path(MAPFUSE_SOURCE_DIR) / "configs";
  CHECK(io::readDocument(configs / "tile.json") == paramsToJson(stages::TileParams{}));
  CHECK(io::readDocument(configs / "balance.json") == paramsToJson(stages::BalanceParams{}));
  CHECK(io::readDocument(configs / "stitch.json") == paramsToJson(tiling::StitchParams{}));
}

TEST_CASE("tile and stitch apps chain on disk and report bad input by exit code", "[tiling][app]") {
  const auto dir = test::tempDir("tile-app");
  io::writeLsm(dir / "a.cbor", straightDrive("a", 5.0));
  io::writeLsm(dir / "b.json", straightDrive("b", -5.0));
  const std::string tile = test::appPath("tile").string();
  REQUIRE(test::runCommand(tile + " -q " + (dir / "a.cbor").string() + " " +
                           (dir / "b.json").string() + " -o " + (dir / "tiles").string() +
                           " --tile-size 200 --margin 20 > " + (dir / "stdout.txt").string()) == 0);
  const io::Json manifest = io::readDocument(dir / "tiles" / "tiles.json");
  // x from -300 to 300 with 200 m tiles: tiles -2..1 in x, -1 and 0 in y (both drives near y = 0).
  CHECK(manifest["tiles"].size() == 8);
  CHECK(std::filesystem::exists(dir / "tiles" / "tile.summary.json"));
  CHECK(std::filesystem::exists(dir / "tiles" / "tile.config.json"));
  // stdout lists the tiles, one per line, for shell pipelines.
  const std::string listed = test::readText(dir / "stdout.txt");
  CHECK(std::count(listed.begin(), listed.end(), '\n') == 8);
  const Lsm part = io::readLsm(dir / "tiles" / "tile_0_0" / "a.cbor");
  for (const auto& k : part.keyframes) CHECK(k.T_frame_body.translation().x() >= -20.0);

  // An LSM that is not georeferenced: bad input, exit 3, and the earlier outputs survive.
  Lsm odom = straightDrive("c", 0.0);
  odom.frame = LsmFrame::kOdom;
  io::writeLsm(dir / "c.json", odom);
  CHECK(test::runCommand(tile + " -q " + (dir / "c.json").string() + " -o " +
                         (dir / "tiles").string() + " 2>/dev/null") == 3);
  CHECK(io::readDocument(dir / "tiles" / "tiles.json") == manifest);
  CHECK(test::runCommand(tile + " -q " + (dir / "missing.json").string() + " -o " +
                         (dir / "t2").string() + " 2>/dev/null") == 4);
  test::writeText(dir / "bad.json", R"({"tile_sise": 10})");
  CHECK(test::runCommand(tile + " --config " + (dir / "bad.json").string() + " " +
                         (dir / "a.cbor").string() + " -o " + (dir / "t3").string() +
                         " 2>/dev/null") == 2);
}

TEST_CASE("the tile of a path is read from its tile_<ix>_<iy> folder", "[tiling]") {
  CHECK(stages::tileOfPath("out/tile_m2_3/aggregate/map.cbor") == tiling::TileKey{-2, 3});
  CHECK_THROWS_AS(stages::tileOfPath("out/tiles/map.cbor"), ParseError);
}
