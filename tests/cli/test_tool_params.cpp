// Every tool's parameters, checked from their declarations (issue 23: a parameter's name,
// default and rule said once; issue 19: every number bounded, finite, range-checked before it is
// narrowed, wherever it comes from).
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <set>

#include "mapfuse/cli/params.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/stages/align.hpp"
#include "mapfuse/stages/balance.hpp"
#include "mapfuse/stages/evaluate_changes.hpp"
#include "mapfuse/stages/evaluate_voxels.hpp"
#include "mapfuse/stages/georef.hpp"
#include "mapfuse/stages/lidar_semantic_map.hpp"
#include "mapfuse/stages/localize.hpp"
#include "mapfuse/stages/lsm_build.hpp"
#include "mapfuse/stages/simulate.hpp"
#include "mapfuse/stages/simulate_lidar.hpp"
#include "mapfuse/stages/stitch.hpp"
#include "mapfuse/stages/tile.hpp"
#include "mapfuse/stages/update.hpp"

using namespace mapfuse;
namespace fs = std::filesystem;

namespace {
/// Sets the numeric parameter `key` to `value` (as its type holds it).
struct SetNumber {
  std::string key;
  double value;
  bool found = false;
  template <class T, class... Rule>
  void operator()(const char* k, T& field, const char*, const char*, const Rule&...) {
    if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>)
      if (key == k) {
        field = static_cast<T>(value);
        found = true;
      }
  }
  template <class T>
  void relation(const char*, const T&, bool, const char*) {}
};

std::string lineOf(const std::string& file, int line) {
  // __FILE__ is relative to the build folder (where the compiler ran) when the compile line held
  // relative paths: ccache's base_dir, -ffile-prefix-map.
  const fs::path path = fs::path(file).is_absolute()
                            ? fs::path(file)
                            : fs::path(MAPFUSE_BIN_DIR).parent_path() / file;
  std::ifstream in(path);
  std::string text;
  for (int i = 0; i < line && std::getline(in, text); ++i) {
  }
  return text;
}

/// A number just outside one end of a range (or nothing when that end is open-ended).
std::optional<double> outside(double end, bool open, bool below, bool integer) {
  if (!std::isfinite(end)) return std::nullopt;
  if (open) return end;
  const double step = integer ? 1.0 : std::max(1e-9, std::abs(end) * 1e-6);
  return below ? end - step : end + step;
}

template <class Params>
void checkTool(const std::string& tool) {
  INFO("tool " << tool);
  const auto decls = paramDeclarations<Params>();
  REQUIRE_FALSE(decls.empty());
  std::map<std::string, std::string> where;
  for (const auto& d : decls) {
    INFO("key " << d.key << " declared at " << d.file << ":" << d.line);
    // one declaration per key, in a header, on the line that names it
    CHECK(where.emplace(d.key, d.file + ":" + std::to_string(d.line)).second);
    CHECK(fs::path(d.file).extension() == ".hpp");
    CHECK(lineOf(d.file, d.line).find('"' + d.key + '"') != std::string::npos);
    CHECK_FALSE(d.help.empty());
    if (d.kind == "integer" || d.kind == "number") {
      // every number has a rule, refused outside it from a config file, naming file and key
      CHECK_FALSE(d.rule.empty());
      CHECK((std::isfinite(d.range.lo) || std::isfinite(d.range.hi)));
      const bool integer = d.kind == "integer";
      for (const auto& bad : {outside(d.range.lo, d.range.lo_open, true, integer),
                              outside(d.range.hi, d.range.hi_open, false, integer)}) {
        if (!bad) continue;
        Params p;
        nlohmann::json j = {
            {d.key, integer ? nlohmann::json(std::llround(*bad)) : nlohmann::json(*bad)}};
        INFO("value " << j.dump());
        CHECK_THROWS_WITH(paramsFromJson(p, j, tool + ".json"),
                          Catch::Contains(tool + ".json") && Catch::Contains(d.key));
      }
      if (integer) {  // a value its type cannot hold is refused, not wrapped
        Params p;
        CHECK_THROWS_AS(paramsFromJson(p, {{d.key, 4294967297LL * 4}}, "c.json"), ConfigError);
        CHECK_THROWS_AS(paramsFromJson(p, {{d.key, -4294967297LL * 4}}, "c.json"), ConfigError);
      } else {  // NaN and infinities (the command line can give them) are refused
        for (const double bad : {std::nan(""), std::numeric_limits<double>::infinity()}) {
          Params p;
          SetNumber set{d.key, bad};
          p.visit(set);
          REQUIRE(set.found);
          CHECK_THROWS_WITH(validateParams(p), Catch::Contains(d.key));
        }
      }
    }
    if (d.kind == "list") {
      // a list has a size rule and a range for each value: an empty list, and the default list
      // with its first value just outside either end, are refused naming file and key
      CHECK_FALSE(d.rule.empty());
      CHECK((std::isfinite(d.range.lo) || std::isfinite(d.range.hi)));
      std::vector<nlohmann::json> bad_lists = {nlohmann::json::array()};
      for (const auto& bad : {outside(d.range.lo, d.range.lo_open, true, false),
                              outside(d.range.hi, d.range.hi_open, false, false)}) {
        if (!bad) continue;
        nlohmann::json list = paramsToJson(Params{})[d.key];
        list[0] = *bad;
        bad_lists.push_back(list);
      }
      for (const auto& list : bad_lists) {
        Params p;
        INFO("value " << list.dump());
        CHECK_THROWS_WITH(paramsFromJson(p, {{d.key, list}}, tool + ".json"),
                          Catch::Contains(tool + ".json") && Catch::Contains(d.key));
      }
    }
    Params p;  // null is not a value
    CHECK_THROWS_AS(paramsFromJson(p, {{d.key, nullptr}}, "c.json"), ConfigError);
  }
  // the defaults are valid and configs/<tool>.json mirrors them
  CHECK_NOTHROW(validateParams(Params{}));
  const auto config = fs::path(MAPFUSE_SOURCE_DIR) / "configs" / (tool + ".json");
  CHECK(io::readDocument(config) == paramsToJson(Params{}));
}
}  // namespace

TEST_CASE("every tool's parameters are declared once, bounded and refused outside", "[cli]") {
  checkTool<stages::AlignParams>("align");
  checkTool<stages::GeorefParams>("georef");
  checkTool<stages::TileParams>("tile");
  checkTool<stages::BalanceParams>("balance");
  checkTool<tiling::StitchParams>("stitch");
  checkTool<stages::LsmBuildParams>("lsm-build");
  checkTool<stages::SimulateParams>("simulate");
  checkTool<stages::SimulateLidarParams>("simulate-lidar");
  checkTool<stages::EvaluateVoxelsParams>("evaluate-voxels");
  checkTool<stages::EvaluateChangesParams>("evaluate-changes");
  checkTool<stages::UpdateParams>("update");
  checkTool<stages::LocalizeParams>("localize");
  checkTool<stages::LidarSemanticMapParams>("lidar-semantic-map");
}
