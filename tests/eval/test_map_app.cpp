#include <catch2/catch.hpp>

#include "mapfuse/cli/params.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/vector_map_io.hpp"
#include "mapfuse/stages/evaluate_map.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;
namespace fs = std::filesystem;

namespace {

std::string quoted(const fs::path& p) {
  return "'" + p.string() + "'";
}

VectorMap simpleMap(double dy) {
  VectorMap m;
  m.origin = {49.0, 8.4, 110.0};
  for (int l = 0; l < 2; ++l) {
    MapInstance i;
    i.id = l + 1;
    i.cls = CrowdClass::kLaneLine;
    i.points = {{0, 3.5 * l + dy, 0}, {50, 3.5 * l + dy, 0}};
    i.support.drives = 4;
    m.instances.push_back(i);
  }
  MapInstance p;
  p.id = 10;
  p.cls = CrowdClass::kPole;
  p.points = {{10, -3 + dy, 0}};
  m.instances.push_back(p);
  return m;
}

int runEvaluate(const std::string& args) {
  return test::runCommand(quoted(test::appPath("evaluate")) + " map -q " + args +
                          " >/dev/null 2>&1");
}

}  // namespace

TEST_CASE("configs/evaluate.json mirrors the evaluate map defaults", "[eval][config]") {
  const stages::EvaluateMapParams defaults;
  validateParams(defaults);
  CHECK(io::readDocument(fs::path(MAPFUSE_SOURCE_DIR) / "configs/evaluate.json") ==
        paramsToJson(defaults));
}

TEST_CASE("evaluate map refuses a coverage wedge that cannot see", "[eval][config]") {
  stages::EvaluateMapParams p;
  p.coverage.half_fov_deg = 0.0;
  CHECK_THROWS_AS(validateParams(p), ConfigError);
  p.coverage.half_fov_deg = 91.0;
  CHECK_THROWS_AS(validateParams(p), ConfigError);
  p = stages::EvaluateMapParams();
  p.coverage.range = 0.0;
  CHECK_THROWS_AS(validateParams(p), ConfigError);
  p.coverage.range = 22.0;
  CHECK_NOTHROW(validateParams(p));
}

TEST_CASE("evaluate map app: outputs, several maps and exit codes", "[eval][app]") {
  const auto dir = test::tempDir("eval-app");
  io::writeVectorMap(dir / "truth.json", simpleMap(0.0));
  io::writeVectorMap(dir / "a.cbor", simpleMap(0.1));
  io::writeVectorMap(dir / "b.json", simpleMap(0.05));
  const auto out = dir / "out";
  REQUIRE(runEvaluate("--map " + quoted(dir / "a.cbor") + " --truth " + quoted(dir / "truth.json") +
                      " -o " + quoted(out)) == 0);
  for (const char* f :
       {"evaluate.summary.json", "evaluate.config.json", "evaluate.md", "error_per_class.png"})
    CHECK(fs::exists(out / f));
  const auto summary = io::readDocument(out / "evaluate.summary.json");
  const auto& lane = summary["maps"][0]["classes"][0];
  CHECK(lane["class"] == "lane_line");
  CHECK(lane["absolute_error"]["mean"].get<double>() == Approx(0.1).margin(1e-9));
  CHECK(summary["maps"][0]["traversals"] == 4);  // from the instance support
  CHECK_THAT(test::readText(out / "evaluate.md"), Catch::Contains("| lane_line |"));

  // two maps: error versus traversals
  const auto out2 = dir / "out2";
  REQUIRE(runEvaluate("--map " + quoted(dir / "a.cbor") + " " + quoted(dir / "b.json") +
                      " --traversals 5 50 --truth " + quoted(dir / "truth.json") + " -o " +
                      quoted(out2)) == 0);
  CHECK(fs::exists(out2 / "error_vs_traversals.png"));
  CHECK_THAT(test::readText(out2 / "evaluate.md"), Catch::Contains("versus traversals"));

  // exit codes
  test::writeText(dir / "cfg.json", "{\"line_tolerence\": 1}");
  CHECK(runEvaluate("--config " + quoted(dir / "cfg.json") + " --map " + quoted(dir / "a.cbor") +
                    " --truth " + quoted(dir / "truth.json") + " -o " + quoted(out)) == 2);
  test::writeText(dir / "cfg2.json", "{\"line_tolerance\": 0.01}");
  CHECK(runEvaluate("--config " + quoted(dir / "cfg2.json") + " --map " + quoted(dir / "a.cbor") +
                    " --truth " + quoted(dir / "truth.json") + " -o " + quoted(dir / "out3")) == 0);
  CHECK(io::readDocument(dir / "out3" / "evaluate.config.json")["line_tolerance"] == 0.01);
  test::writeText(dir / "broken.json", "{\"format\": \"mapfuse.vector_map\", \"version\": 1}");
  CHECK(runEvaluate("--map " + quoted(dir / "broken.json") + " --truth " +
                    quoted(dir / "truth.json") + " -o " + quoted(out)) == 3);
  CHECK(runEvaluate("--map " + quoted(dir / "nope.json") + " --truth " +
                    quoted(dir / "truth.json") + " -o " + quoted(out)) == 4);
  CHECK(runEvaluate("--truth " + quoted(dir / "truth.json") + " -o " + quoted(out)) == 2);
  CHECK(runEvaluate("--map " + quoted(dir / "a.cbor") + " --traversals 1 2 --truth " +
                    quoted(dir / "truth.json") + " -o " + quoted(out)) == 3);
  CHECK(test::runCommand(quoted(test::appPath("evaluate")) + " >/dev/null 2>&1") == 2);
}

TEST_CASE("evaluate map app: values that would exhaust memory or time are refused by name",
          "[eval][app][config]") {
  const auto dir = test::tempDir("eval-bounds");
  io::writeVectorMap(dir / "truth.json", simpleMap(0.0));
  // {option value, key the message names}: refused before any map is read (exit 2)
  const std::pair<const char*, const char*> cases[] = {
      {"--sample-step 1e-7", "sample_step"},        // 1e7 samples per metre: out of memory
      {"--line-tolerance 1e6", "line_tolerance"},   // every segment a candidate of every sample
      {"--coverage-range 1e9", "coverage_range"},   // every pose in one grid cell
      {"--lane-width-max 1.5", "lane_width_max"}};  // below lane_width_min: no lane at all
  for (const auto& [option, key] : cases) {
    INFO(option);
    const auto err = dir / "err.txt";
    CHECK(test::runCommand(quoted(test::appPath("evaluate")) + " map " + option + " --map " +
                           quoted(dir / "none.json") + " --truth " + quoted(dir / "truth.json") +
                           " -o " + quoted(dir / "out") + " >/dev/null 2>" + quoted(err)) == 2);
    CHECK_THAT(test::readText(err), Catch::Contains(key));
  }
  // a value from --config is checked too, and the message names the file and the key
  test::writeText(dir / "cfg.json", "{\"sample_step\": 1e-7}");
  const auto err = dir / "err.txt";
  CHECK(test::runCommand(quoted(test::appPath("evaluate")) + " map --config " +
                         quoted(dir / "cfg.json") + " --map " + quoted(dir / "none.json") +
                         " --truth " + quoted(dir / "truth.json") + " -o " + quoted(dir / "out") +
                         " >/dev/null 2>" + quoted(err)) == 2);
  CHECK_THAT(test::readText(err), Catch::Contains("cfg.json") && Catch::Contains("sample_step"));
}

TEST_CASE("evaluate map reads the traversals of aggregate.summary.json checked", "[eval][bounds]") {
  // The count was narrowed to int unchecked (4294967301 drives read as 5) and a summary of
  // another shape was ignored; now a ParseError names the summary and the field.
  const fs::path dir = test::tempDir("eval_summary");
  const fs::path map = dir / "map.cbor";
  const VectorMap m = simpleMap(0.0);
  CHECK(stages::traversalsOf(map, m) == 4);  // no summary: the largest instance support
  auto summary = [&](const std::string& text) {
    test::writeText(dir / "aggregate.summary.json", text);
  };
  summary(R"({"inputs": {"drives": 12, "lsms": 12}})");
  CHECK(stages::traversalsOf(map, m) == 12);
  summary(R"({"inputs": {"lsms": 12}})");
  CHECK(stages::traversalsOf(map, m) == 4);
  for (const char* bad : {R"({"inputs": {"drives": 4294967301}})", R"({"inputs": {"drives": -1}})",
                          R"({"inputs": {"drives": 2.5}})", R"({"inputs": [1]})"}) {
    summary(bad);
    try {
      stages::traversalsOf(map, m);
      FAIL("accepted " << bad);
    } catch (const ParseError& e) {
      CHECK_THAT(std::string(e.what()),
                 Catch::Contains("aggregate.summary.json") && Catch::Contains("inputs"));
    }
  }
}
