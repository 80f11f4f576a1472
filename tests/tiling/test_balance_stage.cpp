// Stage `balance` on disk: tiles cut by `tile`, align outputs made by hand from known georef
// errors (each registration group at the mean error of its own drives, as align leaves it),
// then every placed drive must sit at the batch-wide mean error.
#include <catch2/catch.hpp>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/lsm_io.hpp"
#include "mapfuse/stages/balance.hpp"
#include "mapfuse/stages/tile.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;
namespace fs = std::filesystem;

namespace {
constexpr double kPlacedTol = 0.02;  // m: exact model, no noise

// Four drives along x over two 200 m tiles (ix -1 and 0), each with its own georef error.
const std::vector<Eigen::Vector3d> kErrors = {
    {1.5, 0.5, 0.0}, {-2.0, 1.0, 0.0}, {0.5, -2.5, 0.0}, {2.5, 2.0, 0.0}};

Lsm georefDrive(int d) {
  Lsm lsm;
  lsm.drive_id = "drive" + std::to_string(d);
  lsm.frame = LsmFrame::kEnu;
  lsm.origin = geo::GeoOrigin{49.0, 8.4, 110.0};
  for (int i = 0; i <= 36; ++i) {
    Keyframe k;
    k.id = i;
    k.stamp = 100.0 * d + i;
    // True position (y = 100 + 4 d, mid-row) plus the drive's georef error.
    k.T_frame_body.translation() =
        Eigen::Vector3d(-180.0 + 10.0 * i, 100.0 + 4.0 * d, 0) + kErrors[d];
    lsm.keyframes.push_back(k);
  }
  return lsm;
}

// What align would write for one tile: each group moved onto the mean error of its drives.
void fakeAlign(const fs::path& tiles, const std::string& tile,
               const std::vector<std::vector<int>>& groups) {
  const fs::path dir = tiles / tile;
  nlohmann::json inputs = nlohmann::json::array(), pairs = nlohmann::json::array();
  std::map<int, int> index;  // drive -> align input index
  for (int d = 0; d < int(kErrors.size()); ++d) {
    index[d] = int(inputs.size());
    inputs.push_back((dir / ("drive" + std::to_string(d) + ".cbor")).string());
  }
  for (const auto& g : groups) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (int d : g) mean += kErrors[d] / double(g.size());
    for (std::size_t i = 0; i < g.size(); ++i) {
      Lsm lsm = io::readLsm(dir / ("drive" + std::to_string(g[i]) + ".cbor"));
      for (auto& k : lsm.keyframes) k.T_frame_body.translation() += mean - kErrors[g[i]];
      io::writeLsm(dir / "align" / ("drive" + std::to_string(g[i]) + ".cbor"), lsm);
      if (i > 0)
        pairs.push_back({{"lsm_a", index[g[i - 1]]},
                         {"lsm_b", index[g[i]]},
                         {"accepted", true},
                         {"pcm_consistent", true},
                         {"graph_outlier", false}});
    }
  }
  // A registration the pose graph rejected links nothing.
  pairs.push_back({{"lsm_a", 0},
                   {"lsm_b", 3},
                   {"accepted", true},
                   {"pcm_consistent", true},
                   {"graph_outlier", true}});
  io::writeDocument(dir / "align" / "align.summary.json",
                    {{"format", "mapfuse.summary"}, {"inputs", inputs}, {"pairs", pairs}}, 1);
}

fs::path tiledBatch(const std::string& name) {
  const fs::path dir = test::tempDir(name);
  std::vector<std::string> files;
  for (int d = 0; d < int(kErrors.size()); ++d) {
    files.push_back((dir / ("drive" + std::to_string(d) + ".cbor")).string());
    io::writeLsm(files.back(), georefDrive(d));
  }
  stages::TileParams tp;
  tp.tile_size = 200.0;
  tp.margin = 20.0;
  const auto manifest = stages::runTile(files, dir / "tiles", tp);
  REQUIRE(manifest["tiles"].size() == 2);
  // West tile: one road, every drive registered together. East tile: two roads that never meet.
  fakeAlign(dir / "tiles", "tile_m1_0", {{0, 1, 2, 3}});
  fakeAlign(dir / "tiles", "tile_0_0", {{0, 1}, {2, 3}});
  return dir;
}
}  // namespace

TEST_CASE("balance moves every registration group to the batch-wide mean error",
          "[tiling][balance]") {
  const fs::path dir = tiledBatch("balance-stage");
  const auto summary =
      stages::runBalance(dir / "tiles" / "tiles.json", dir / "balance", stages::BalanceParams{});
  CHECK(summary["tiles"] == 2);
  CHECK(summary["groups"] == 3);
  CHECK(summary["drives"] == 4);
  CHECK(summary["pieces"] == 8);
  CHECK(fs::exists(dir / "balance" / "balance.summary.json"));
  CHECK(fs::exists(dir / "balance" / "balance.config.json"));

  Eigen::Vector3d batch_mean = Eigen::Vector3d::Zero();
  for (const auto& e : kErrors) batch_mean += e / double(kErrors.size());
  // Unbalanced, the east tile's two groups sit 2.0 m apart; placed, every drive in both tiles
  // sits at the batch mean, elements with it (they hang on the keyframes).
  for (const std::string tile : {"tile_m1_0", "tile_0_0"})
    for (int d = 0; d < int(kErrors.size()); ++d) {
      const std::string file = "drive" + std::to_string(d) + ".cbor";
      const Lsm placed = io::readLsm(dir / "balance" / tile / file);
      const Lsm georef = io::readLsm(dir / "tiles" / tile / file);
      REQUIRE(placed.keyframes.size() == georef.keyframes.size());
      for (std::size_t k = 0; k < placed.keyframes.size(); ++k) {
        const Eigen::Vector3d truth = georef.keyframes[k].T_frame_body.translation() - kErrors[d];
        CHECK((placed.keyframes[k].T_frame_body.translation() - truth - batch_mean).norm() <
              kPlacedTol);
      }
    }
}

TEST_CASE("balance refuses a tile without align output and keeps what it wrote before",
          "[tiling][balance]") {
  const fs::path dir = tiledBatch("balance-missing");
  const fs::path tiles_json = dir / "tiles" / "tiles.json";
  stages::runBalance(tiles_json, dir / "balance", stages::BalanceParams{});
  const std::string before = test::readText(dir / "balance" / "tile_0_0" / "drive0.cbor");

  fs::remove(dir / "tiles" / "tile_0_0" / "align" / "drive2.cbor");
  CHECK_THROWS_WITH(stages::runBalance(tiles_json, dir / "balance", stages::BalanceParams{}),
                    Catch::Contains("tile_0_0/align/drive2.cbor"));
  fs::remove(dir / "tiles" / "tile_0_0" / "align" / "align.summary.json");
  CHECK_THROWS_AS(stages::runBalance(tiles_json, dir / "balance", stages::BalanceParams{}),
                  InputError);
  CHECK(test::readText(dir / "balance" / "tile_0_0" / "drive0.cbor") == before);

  // The app: bad input is exit 3, an unknown configuration key exit 2.
  const std::string balance = test::appPath("balance").string();
  CHECK(test::runCommand(balance + " -q --tiles " + tiles_json.string() + " -o " +
                         (dir / "b2").string() + " 2>/dev/null") == 3);
  test::writeText(dir / "bad.json", R"({"bias_wlak": 0.1})");
  CHECK(test::runCommand(balance + " --config " + (dir / "bad.json").string() + " --tiles " +
                         tiles_json.string() + " -o " + (dir / "b3").string() + " 2>/dev/null") ==
        2);
  CHECK_FALSE(fs::exists(dir / "b2" / "balance.summary.json"));
}

TEST_CASE("balance names the file and field of a broken align summary", "[tiling][balance]") {
  const fs::path dir = tiledBatch("balance-broken");
  const fs::path tiles_json = dir / "tiles" / "tiles.json";
  stages::runBalance(tiles_json, dir / "balance", stages::BalanceParams{});
  const std::string before = test::readText(dir / "balance" / "tile_0_0" / "drive0.cbor");
  const fs::path summary = dir / "tiles" / "tile_0_0" / "align" / "align.summary.json";
  io::Json doc = io::readDocument(summary);
  doc["pairs"][0]["lsm_b"] = 99;  // no such input
  io::writeDocument(summary, doc, 1);
  CHECK_THROWS_WITH(stages::runBalance(tiles_json, dir / "balance", stages::BalanceParams{}),
                    Catch::Contains("align.summary.json") && Catch::Contains("lsm_a / lsm_b"));
  doc["pairs"][0].erase("pcm_consistent");
  io::writeDocument(summary, doc, 1);
  CHECK_THROWS_WITH(stages::runBalance(tiles_json, dir / "balance", stages::BalanceParams{}),
                    Catch::Contains("pcm_consistent"));
  test::writeText(summary, "{ not json");
  CHECK_THROWS_AS(stages::runBalance(tiles_json, dir / "balance", stages::BalanceParams{}),
                  ParseError);
  // Bad input (exit 3) from the app too, and what balance wrote before is still there.
  CHECK(test::runCommand(test::appPath("balance").string() + " -q --tiles " + tiles_json.string() +
                         " -o " + (dir / "balance").string() + " 2>/dev/null") == 3);
  CHECK(test::readText(dir / "balance" / "tile_0_0" / "drive0.cbor") == before);
}
