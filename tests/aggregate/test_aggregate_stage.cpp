#include <catch2/catch.hpp>
#include <pugixml.hpp>

#include "mapfuse/cli/params.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/lsm_io.hpp"
#include "mapfuse/io/vector_map_io.hpp"
#include "mapfuse/stages/aggregate.hpp"
#include "support/test_support.hpp"
#include "synthetic_world.hpp"

using namespace mapfuse;
namespace fs = std::filesystem;

namespace {

// A synthetic world of `drives` drives over `length` m of road and its LSMs, written as CBOR
// files below `dir` (their paths in `files`).
struct SynthLsms {
  test::SynthWorld world;
  std::vector<std::string> files;
};
SynthLsms writeSynthLsms(const fs::path& dir, int drives, double length) {
  test::SynthOptions o;
  o.drives = drives;
  o.length = length;
  SynthLsms s{test::makeSynthWorld(o), {}};
  for (const auto& l : s.world.lsms) {
    s.files.push_back((dir / (l.drive_id + ".lsm.cbor")).string());
    io::writeLsm(s.files.back(), l);
  }
  return s;
}

std::string quoted(const fs::path& p) {
  return "'" + p.string() + "'";
}

int runAggregateApp(const std::string& args) {
  return test::runCommand(quoted(test::appPath("aggregate")) + " -q " + args + " >/dev/null 2>&1");
}

}  // namespace

TEST_CASE("configs/aggregate.json mirrors the defaults, which are valid", "[aggregate][config]") {
  const stages::AggregateParams defaults;
  validateParams(defaults);
  const auto file = io::readDocument(fs::path(MAPFUSE_SOURCE_DIR) / "configs/aggregate.json");
  CHECK(file == paramsToJson(defaults));
  stages::AggregateParams bad;
  bad.aggregator.lanes.link_max_pts = 0;
  CHECK_THROWS_AS(validateParams(bad), ConfigError);
}

TEST_CASE("the aggregate stage writes every output and a size summary", "[aggregate][stage]") {
  const auto dir = test::tempDir("agg-stage");
  const auto [w, files] = writeSynthLsms(dir, 6, test::SynthOptions{}.length);
  const auto out = dir / "out";
  const auto summary = stages::toJson(stages::runAggregate(files, out, stages::AggregateParams{}));
  for (const char* f : {"map.cbor", "map.json", "map.geojson", "map.osm", "map.osm.mapfuse.json",
                        "map.png", "aggregate.summary.json", "aggregate.config.json"})
    CHECK(fs::exists(out / f));
  // the compact CBOR and the JSON hold the same instances
  const VectorMap cbor = io::readVectorMap(out / "map.cbor");
  const VectorMap json = io::readVectorMap(out / "map.json");
  REQUIRE(cbor.instances.size() == json.instances.size());
  CHECK(cbor.instances.size() == w.truth.instances.size());
  // road length: one 200 m road driven both ways (keyframes cover 0..175 m + the view)
  constexpr double kRoadKmTolerance = 0.02;
  CHECK(summary["size"]["road_km"].get<double>() == Approx(0.175).margin(kRoadKmTolerance));
  CHECK(summary["size"]["kb_per_km"].get<double>() > 0.0);
  CHECK(summary["inputs"]["drives"] == 6);
  // OSM: lane lines as line_thin ways with a subtype, poles as tagged nodes
  pugi::xml_document osm;
  REQUIRE(osm.load_file((out / "map.osm").c_str()));
  int dashed = 0, solid = 0, poles = 0;
  for (auto way : osm.child("osm").children("way"))
    for (auto tag : way.children("tag"))
      if (std::string(tag.attribute("v").value()) == "line_thin") {
        const std::string sub =
            way.find_child_by_attribute("tag", "k", "subtype").attribute("v").value();
        dashed += sub == "dashed";
        solid += sub == "solid";
      }
  for (auto node : osm.child("osm").children("node"))
    poles += std::string(node.find_child_by_attribute("tag", "k", "type").attribute("v").value()) ==
             "pole";
  CHECK(dashed == 1);
  CHECK(solid == 2);
  CHECK(poles == 7);
  CHECK(osm.child("osm").child("node").attribute("lat").as_double() == Approx(49.011).margin(0.01));
}

TEST_CASE("aggregate app: exit codes, lists and intact outputs after a failure",
          "[aggregate][app]") {
  const auto dir = test::tempDir("agg-app");
  const auto [w, files] = writeSynthLsms(dir, 3, 100);
  const auto out = dir / "out";
  test::writeText(dir / "list.txt", files[0] + "\n" + files[1] + "\n# comment\n" + files[2] + "\n");
  REQUIRE(runAggregateApp("-o " + quoted(out) + " @" + quoted(dir / "list.txt")) == 0);
  const std::string before = test::readText(out / "map.cbor");
  // --help lists options with defaults
  CHECK(test::runCommand(quoted(test::appPath("aggregate")) +
                         " --help | grep -q 'max-deviation FLOAT=0.08'") == 0);
  // a malformed LSM: exit 3, previous outputs intact
  test::writeText(dir / "bad.lsm.json",
                  "{\"format\": \"mapfuse.lsm\", \"version\": 1, \"frame\": 7}");
  CHECK(runAggregateApp("-o " + quoted(out) + " " + quoted(dir / "bad.lsm.json")) == 3);
  CHECK(test::readText(out / "map.cbor") == before);
  // an unknown configuration key: exit 2
  test::writeText(dir / "cfg.json", "{\"max_deviaton\": 0.1}");
  CHECK(runAggregateApp("--config " + quoted(dir / "cfg.json") + " -o " + quoted(out) + " " +
                        files[0]) == 2);
  // an origin mismatch: exit 3
  Lsm other = w.lsms[1];
  other.origin->lon += 0.001;
  io::writeLsm(dir / "other.lsm.cbor", other);
  CHECK(runAggregateApp("-o " + quoted(out) + " " + files[0] + " " +
                        quoted(dir / "other.lsm.cbor")) == 3);
  // an LSM still in odom: exit 3
  Lsm odom = w.lsms[0];
  odom.frame = LsmFrame::kOdom;
  io::writeLsm(dir / "odom.lsm.cbor", odom);
  CHECK(runAggregateApp("-o " + quoted(out) + " " + quoted(dir / "odom.lsm.cbor")) == 3);
  // a missing file: exit 4; a bad option value: exit 2
  CHECK(runAggregateApp("-o " + quoted(out) + " " + quoted(dir / "nope.cbor")) == 4);
  CHECK(runAggregateApp("--max-deviation -1 -o " + quoted(out) + " " + files[0]) == 2);
  CHECK(test::readText(out / "map.cbor") == before);
  // stdin list
  CHECK(test::runCommand("printf '%s\\n' " + files[0] + " " + files[1] + " | " +
                         quoted(test::appPath("aggregate")) + " -q -o " + quoted(dir / "out2") +
                         " - >/dev/null 2>&1") == 0);
  CHECK(fs::exists(dir / "out2" / "map.cbor"));
}

TEST_CASE("aggregate app: --method grid_vote runs the Qin baseline and says so",
          "[aggregate][app][grid_vote]") {
  const auto dir = test::tempDir("agg-grid");
  const auto files = writeSynthLsms(dir, 4, 100).files;
  std::string inputs;
  for (const auto& f : files) inputs += " " + quoted(fs::path(f));
  REQUIRE(runAggregateApp("--method grid_vote -o " + quoted(dir / "grid") + inputs) == 0);
  const auto summary = io::readDocument(dir / "grid" / "aggregate.summary.json");
  CHECK(summary["method"] == "grid_vote");
  CHECK(summary["grid_vote"]["voted_cells"].get<int>() > 0);
  CHECK(summary["grid_vote"]["min_votes"] == 3);
  CHECK(summary["classes"]["lane_line"]["instances"] == 3);
  CHECK(io::readDocument(dir / "grid" / "aggregate.config.json")["method"] == "grid_vote");
  // the default is the paper's method, without a grid block; an unknown method: exit 2
  REQUIRE(runAggregateApp("-o " + quoted(dir / "ours") + inputs) == 0);
  const auto ours = io::readDocument(dir / "ours" / "aggregate.summary.json");
  CHECK(ours["method"] == "dbscan_bezier");
  CHECK_FALSE(ours.contains("grid_vote"));
  CHECK(runAggregateApp("--method voting -o " + quoted(dir / "bad") + inputs) == 2);
}

TEST_CASE("aggregate app: values that would exhaust memory or overflow are refused by name",
          "[aggregate][app][config]") {
  const auto dir = test::tempDir("agg-bounds");
  // {option value, key the message names}: each refused before any input is read (exit 2)
  const std::pair<const char*, const char*> cases[] = {
      {"--coordinate-quantum 1e-300", "coordinate_quantum"},  // every coordinate INT64_MIN
      {"--sample-step 1e-7", "sample_step"},                  // 1e7 points per metre of line
      {"--station-step 1e-9", "station_step"},                // arc bridges of 1e9 points per m
      {"--tile-size 1e-6", "tile_size"},                      // observations cut into µm pieces
      {"--road-tolerance 1e-300", "road_tolerance"},          // grid keys overflow
      {"--point-radius 1e6", "point_radius"}};                // every pole a neighbour of all
  for (const auto& [option, key] : cases) {
    INFO(option);
    const auto err = dir / "err.txt";
    CHECK(test::runCommand(quoted(test::appPath("aggregate")) + " " + option + " -o " +
                           quoted(dir / "out") + " " + quoted(dir / "none.lsm.cbor") +
                           " >/dev/null 2>" + quoted(err)) == 2);
    CHECK_THAT(test::readText(err), Catch::Contains(key));
  }
}
