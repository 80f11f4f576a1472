#include <catch2/catch.hpp>

#include "mapfuse/cli/app.hpp"
#include "mapfuse/cli/params.hpp"
#include "mapfuse/io/document.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;

namespace {
struct DemoParams {
  static constexpr const char* kName = "DemoParams";
  double voxel_size = 0.25;  ///< m
  int max_iterations = 30;
  bool use_labels = true;
  std::string method = "sgicp";
  uint64_t seed = 7;

  template <class V>
  void visit(V& v) {
    v("voxel_size", voxel_size, "m", "voxel edge", param::gt(0));
    v("max_iterations", max_iterations, "", "iterations");
    v("use_labels", use_labels, "", "match within a class only");
    v("method", method, "", "icp|sgicp");
    v("seed", seed, "", "random seed");
  }
};

int runWith(std::vector<std::string> args, DemoParams& params, const std::function<void()>& body) {
  CLI::App app("demo", "demo");
  cli::CommonOptions common;
  cli::addCommonOptions(app, common);
  cli::addParamOptions(app, params);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  return cli::run(app, int(argv.size()), argv.data(), [&] {
    validateParams(params);
    body();
  });
}
}  // namespace

TEST_CASE("params serialise to JSON and back, and unknown keys are config errors",
          "[core][params]") {
  DemoParams p;
  const auto j = paramsToJson(p);
  CHECK(j["voxel_size"] == 0.25);
  CHECK(j["method"] == "sgicp");
  DemoParams q;
  q.voxel_size = 9;
  paramsFromJson(q, j, "x.json");
  CHECK(q.voxel_size == 0.25);

  try {
    paramsFromJson(q, io::Json{{"voxel_sise", 0.5}}, "cfg.json");
    FAIL("unknown key accepted");
  } catch (const ConfigError& e) {
    CHECK_THAT(e.what(), Catch::Contains("cfg.json"));
    CHECK_THAT(e.what(), Catch::Contains("voxel_sise"));
    CHECK(e.exitCode() == ExitCode::kUsage);
  }
  CHECK_THROWS_AS(paramsFromJson(q, io::Json{{"max_iterations", "many"}}, "c.json"), ConfigError);
  CHECK_THROWS_AS(paramsFromJson(q, io::Json{{"seed", -1}}, "c.json"), ConfigError);
  CHECK_THROWS_AS(paramsFromJson(q, io::Json::array(), "c.json"), ConfigError);
}

TEST_CASE("validation names the field, the value and the rule", "[core][params]") {
  DemoParams p;
  validateParams(p);  // defaults are valid
  p.voxel_size = -1;
  try {
    validateParams(p);
    FAIL("invalid value accepted");
  } catch (const ConfigError& e) {
    CHECK(std::string(e.what()) ==
          "DemoParams::voxel_size = -1.0. Violated constraint: voxel_size > 0");
  }
}

TEST_CASE("tools map errors to the documented exit codes", "[core][cli]") {
  DemoParams p;
  CHECK(runWith({"demo"}, p, [] {}) == 0);
  CHECK(runWith({"demo", "--help"}, p, [] {}) == 0);
  CHECK(runWith({"demo", "--no-such-option"}, p, [] {}) == 2);
  CHECK(runWith({"demo", "--voxel-size", "-3"}, p, [] {}) == 2);  // fails validation
  p = DemoParams{};
  CHECK(runWith({"demo"}, p, [] { throw ParseError("f.json", "a.b", "bad"); }) == 3);
  CHECK(runWith({"demo"}, p, [] { throw InputError("no overlap"); }) == 3);
  CHECK(runWith({"demo"}, p, [] { throw IoError("f", "cannot open"); }) == 4);
  CHECK(runWith({"demo"}, p, [] { throw std::runtime_error("bug"); }) == 1);
}

TEST_CASE("config file values become defaults and the command line overrides them", "[core][cli]") {
  const auto dir = test::tempDir("cli-config");
  io::writeDocument(dir / "cfg.json", io::Json{{"voxel_size", 0.5}, {"max_iterations", 5}});
  const std::string cfg = (dir / "cfg.json").string();
  std::vector<std::string> args = {"demo", "--config", cfg, "--max-iterations", "12"};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  DemoParams p;
  cli::preloadConfig(int(argv.size()), argv.data(), p);
  CHECK(runWith(args, p, [] {}) == 0);
  CHECK(p.voxel_size == 0.5);     // from the file
  CHECK(p.max_iterations == 12);  // command line wins
  CHECK(p.method == "sgicp");     // untouched default
}

TEST_CASE("input lists come from arguments, list files and stdin", "[core][cli]") {
  const auto dir = test::tempDir("cli-list");
  test::writeText(dir / "list.txt", "# drives\na.cbor\n  b.cbor  \n\nc.cbor\n");
  const auto files = cli::expandInputList({"x.cbor", "@" + (dir / "list.txt").string()});
  CHECK(files == std::vector<std::string>{"x.cbor", "a.cbor", "b.cbor", "c.cbor"});
  CHECK_THROWS_AS(cli::expandInputList({"@" + (dir / "nope.txt").string()}), IoError);
}

namespace {
struct ListParams {
  static constexpr const char* kName = "ListParams";
  std::vector<double> distances = {1.5, 0.75};  ///< m

  template <class V>
  void visit(V& v) {
    v("distances", distances, "m", "per level", param::listOf(1, 3, param::gt(0) & param::le(10)));
  }
};

int runList(std::vector<std::string> args, ListParams& params) {
  CLI::App app("demo", "demo");
  cli::addParamOptions(app, params);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  return cli::run(app, int(argv.size()), argv.data(), [&] { validateParams(params); });
}
}  // namespace

TEST_CASE("list parameters: flag, config array, resolved config and rules", "[core][params]") {
  SECTION("the command line replaces the default list, comma-separated") {
    ListParams p;
    CHECK(runList({"demo", "--distances", "2,1,0.5"}, p) == 0);
    CHECK(p.distances == std::vector<double>{2, 1, 0.5});
    ListParams q;
    CHECK(runList({"demo", "--distances", "3"}, q) == 0);
    CHECK(q.distances == std::vector<double>{3});
  }
  SECTION("a value out of range or too many values is a usage error (exit 2)") {
    ListParams p;
    CHECK(runList({"demo", "--distances", "2,-1"}, p) == 2);
    ListParams q;
    CHECK(runList({"demo", "--distances", "4,3,2,1"}, q) == 2);
  }
  SECTION("config files hold arrays; wrong shapes name the file and key") {
    ListParams p;
    const auto j = paramsToJson(p);
    CHECK(j["distances"] == io::Json::array({1.5, 0.75}));
    paramsFromJson(p, io::Json{{"distances", {4.0}}}, "c.json");
    CHECK(p.distances == std::vector<double>{4.0});
    for (const io::Json& bad : {io::Json(2.0), io::Json::array(), io::Json::array({1, 2, 3, 4}),
                                io::Json::array({1, 0}), io::Json::array({1, "x"})}) {
      INFO(bad.dump());
      CHECK_THROWS_WITH(paramsFromJson(p, io::Json{{"distances", bad}}, "c.json"),
                        Catch::Contains("c.json") && Catch::Contains("distances"));
    }
    CHECK(p.distances == std::vector<double>{4.0});  // a refused file changes nothing
  }
  SECTION("validation names the list and the rule") {
    ListParams p;
    p.distances = {};
    CHECK_THROWS_WITH(validateParams(p), Catch::Contains("ListParams::distances = []") &&
                                             Catch::Contains("1 to 3 values, each in (0, 10]"));
  }
}
