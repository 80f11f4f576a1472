// `evaluate changes` (docs/evaluate.md "evaluate changes"): the truth scored against itself gives
// F1 = 1; a detection with one false removal and one missed change gives the figures counted by
// hand; additions match within added_match_distance only; change files that do not describe the
// before map are refused naming file and field; the tool's outputs and exit codes.
#include <catch2/catch.hpp>

#include "mapfuse/core/error.hpp"
#include "mapfuse/eval/change_metrics.hpp"
#include "mapfuse/eval/change_report.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/map_changes_io.hpp"
#include "mapfuse/io/vector_map_io.hpp"
#include "support/error_matchers.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;
namespace fs = std::filesystem;

namespace {

constexpr double kExact = 1e-12;

MapInstance element(int64_t id, CrowdClass cls, std::vector<Eigen::Vector3d> points) {
  MapInstance m;
  m.id = id;
  m.cls = cls;
  m.points = std::move(points);
  return m;
}

/// Ten elements: poles 1-4, signs 5-6, lane lines 7-10.
VectorMap beforeMap() {
  VectorMap map;
  map.origin = {49.0, 8.4, 110.0};
  for (int i = 1; i <= 4; ++i)
    map.instances.push_back(element(i, CrowdClass::kPole, {{20.0 * i, 5.0, 0.0}}));
  for (int i = 5; i <= 6; ++i)
    map.instances.push_back(element(
        i, CrowdClass::kTrafficSign,
        {{20.0 * i, 5, 2}, {20.0 * i + 0.6, 5, 2}, {20.0 * i + 0.6, 5, 2.6}, {20.0 * i, 5, 2.6}}));
  for (int i = 7; i <= 10; ++i)
    map.instances.push_back(
        element(i, CrowdClass::kLaneLine, {{0, 3.5 * (i - 7), 0}, {200, 3.5 * (i - 7), 0}}));
  return map;
}

MapChange change(ChangeKind kind, const VectorMap& before, int64_t id) {
  MapChange c;
  c.kind = kind;
  for (const auto& m : before.instances)
    if (m.id == id) c.before = m;
  c.cls = c.before->cls;
  if (kind != ChangeKind::kRemoved) c.after = c.before;
  return c;
}

MapChange addedPole(int64_t id, double x, double y) {
  MapChange c;
  c.kind = ChangeKind::kAdded;
  c.cls = CrowdClass::kPole;
  c.after = element(id, CrowdClass::kPole, {{x, y, 0.0}});
  return c;
}

/// True changes: pole 1 removed, pole 2 moved 3 m, lane line 8 retyped, a pole added at (50, 9).
MapChanges truthChanges(const VectorMap& before) {
  MapChanges t;
  t.origin = before.origin;
  t.changes.push_back(change(ChangeKind::kRemoved, before, 1));
  t.changes.push_back(change(ChangeKind::kMoved, before, 2));
  t.changes.back().after->points[0].x() += 3.0;
  t.changes.push_back(change(ChangeKind::kRetyped, before, 8));
  t.changes.back().after->attributes.style = LineStyle::kSolid;
  t.changes.push_back(addedPole(11, 50.0, 9.0));
  return t;
}

std::string quoted(const fs::path& p) {
  return "'" + p.string() + "'";
}

}  // namespace

TEST_CASE("the true changes scored against themselves give F1 = 1", "[eval]") {
  const VectorMap before = beforeMap();
  const MapChanges truth = truthChanges(before);
  const eval::ChangeScores s = eval::scoreChanges(truth, truth, before, {});
  CHECK(s.overall.tp == 4);
  CHECK(s.overall.fp == 0);
  CHECK(s.overall.fn == 0);
  CHECK(*s.overall.f1() == 1.0);
  CHECK(s.unchanged_elements == 7);  // 10 elements, 3 named by true changes
  CHECK(s.false_removals == 0);
  CHECK(*s.falseRemovalRate() == 0.0);
  CHECK(*s.by_kind.at(ChangeKind::kAdded).f1() == 1.0);
  CHECK(!s.by_kind.at(ChangeKind::kRestriped).f1());  // no such change: undefined
  CHECK(*s.by_class.at(CrowdClass::kPole).f1() == 1.0);
  CHECK(s.by_class.at(CrowdClass::kPole).tp == 3);
}

TEST_CASE("one false removal and one missed change give the counted figures", "[eval]") {
  const VectorMap before = beforeMap();
  const MapChanges truth = truthChanges(before);
  MapChanges detected = truth;
  detected.changes.erase(detected.changes.begin() + 1);                 // the move is missed
  detected.changes.push_back(change(ChangeKind::kRemoved, before, 5));  // sign 5 never changed
  const eval::ChangeScores s = eval::scoreChanges(detected, truth, before, {});
  CHECK(s.overall.tp == 3);
  CHECK(s.overall.fp == 1);
  CHECK(s.overall.fn == 1);
  CHECK(std::abs(*s.overall.precision() - 0.75) < kExact);
  CHECK(std::abs(*s.overall.recall() - 0.75) < kExact);
  CHECK(std::abs(*s.overall.f1() - 0.75) < kExact);
  const eval::ChangeCounts& removed = s.by_kind.at(ChangeKind::kRemoved);
  CHECK(std::abs(*removed.precision() - 0.5) < kExact);
  CHECK(*removed.recall() == 1.0);
  CHECK(std::abs(*removed.f1() - 2.0 / 3.0) < kExact);
  const eval::ChangeCounts& moved = s.by_kind.at(ChangeKind::kMoved);
  CHECK(!moved.precision());
  CHECK(*moved.recall() == 0.0);
  CHECK(*moved.f1() == 0.0);
  CHECK(s.by_class.at(CrowdClass::kTrafficSign).fp == 1);
  CHECK(s.false_removals == 1);
  CHECK(std::abs(*s.falseRemovalRate() - 1.0 / 7.0) < kExact);
  REQUIRE(s.missed.size() == 1);
  CHECK(*s.missed[0].before_id == 2);
  REQUIRE(s.wrong.size() == 1);
  CHECK(*s.wrong[0].before_id == 5);
  const auto doc = eval::changeScoresToJson(s, {});
  CHECK(doc["false_removals"]["within_bound"] == false);  // 14 % > 0.5 %
  CHECK_THAT(eval::changeScoresToMarkdown(s, {}, "t"),
             Catch::Contains("| all changes | 3 | 1 | 1 | 75.0 | 75.0 | 75.0 |") &&
                 Catch::Contains("False removals of unchanged elements: 1 of 7 (14.3 %"));
}

TEST_CASE("additions match within added_match_distance and the same class only", "[eval]") {
  const VectorMap before = beforeMap();
  MapChanges truth;
  truth.origin = before.origin;
  truth.changes = {addedPole(11, 50.0, 9.0), addedPole(12, 150.0, 9.0)};
  MapChanges detected = truth;
  detected.changes[0] = addedPole(500, 50.0, 9.0 + 2.9);   // within 3 m: matched
  detected.changes[1] = addedPole(501, 150.0 + 3.1, 9.0);  // beyond: a false and a missed one
  eval::ChangeScoreSettings settings;
  eval::ChangeScores s = eval::scoreChanges(detected, truth, before, settings);
  CHECK(s.overall.tp == 1);
  CHECK(s.overall.fp == 1);
  CHECK(s.overall.fn == 1);
  settings.added_match_distance = 3.2;
  CHECK(eval::scoreChanges(detected, truth, before, settings).overall.tp == 2);
  detected.changes[0].cls = detected.changes[0].after->cls = CrowdClass::kTrafficLight;
  CHECK(eval::scoreChanges(detected, truth, before, settings).overall.tp == 1);
  // A true move reported as a removal is a wrong removal and a missed move, not a false removal.
  MapChanges moved;
  moved.origin = before.origin;
  moved.changes = {change(ChangeKind::kMoved, before, 3)};
  MapChanges removal = moved;
  removal.changes = {change(ChangeKind::kRemoved, before, 3)};
  s = eval::scoreChanges(removal, moved, before, {});
  CHECK(s.overall.tp == 0);
  CHECK(s.overall.fp == 1);
  CHECK(s.overall.fn == 1);
  CHECK(s.false_removals == 0);
}

TEST_CASE("change files must describe the before map", "[eval]") {
  const VectorMap before = beforeMap();
  MapChanges c = truthChanges(before);
  CHECK_NOTHROW(eval::checkAgainstBefore(c, "t.json", before, "b.json"));
  c.changes[2].before->id = 77;
  CHECK_THROWS_MATCHES(eval::checkAgainstBefore(c, "t.json", before, "b.json"), ParseError,
                       test::ParseErrorAt("changes[2].before_id", "t.json", "not an element"));
  c = truthChanges(before);
  c.changes[0].cls = CrowdClass::kTrafficLight;
  CHECK_THROWS_MATCHES(eval::checkAgainstBefore(c, "t.json", before, "b.json"), ParseError,
                       test::ParseErrorAt("changes[0].before_id", "t.json", "is a pole"));
  c = truthChanges(before);
  c.origin.lat += 1e-4;
  CHECK_THROWS_AS(eval::checkAgainstBefore(c, "t.json", before, "b.json"), InputError);
}

TEST_CASE("evaluate changes: outputs and exit codes", "[eval][app]") {
  const fs::path dir = test::tempDir("evaluate_changes");
  const VectorMap before = beforeMap();
  io::writeVectorMap(dir / "before.json", before);
  io::writeMapChanges(dir / "truth.json", truthChanges(before));
  const auto run = [&](const std::string& detected, const std::string& out) {
    return test::runCommand(quoted(test::appPath("evaluate")) + " changes -q --detected " +
                            quoted(dir / detected) + " --truth " + quoted(dir / "truth.json") +
                            " --before " + quoted(dir / "before.json") + " -o " +
                            quoted(dir / out) + " >/dev/null 2>" + quoted(dir / (out + ".err")));
  };
  REQUIRE(run("truth.json", "self") == 0);
  const auto summary = test::readSummary(dir / "self", "evaluate-changes");
  CHECK(summary["f1"] == 1.0);
  CHECK(summary["true_changes"] == 4);
  CHECK(summary["false_removals"]["count"] == 0);
  CHECK(fs::exists(dir / "self" / "change-scores.md"));
  CHECK(io::readDocument(dir / "self" / "change-scores.json")["by_kind"]["moved"]["f1"] == 1.0);
  // A malformed detection: exit 3, naming the file and the field, nothing written.
  io::Json bad = io::mapChangesToJson(truthChanges(before));
  bad["changes"][1]["kind"] = "shifted";
  io::writeDocument(dir / "bad.json", bad);
  CHECK(run("bad.json", "bad") == 3);
  CHECK_THAT(test::readText(dir / "bad.err"),
             Catch::Contains("bad.json") && Catch::Contains("changes[1].kind"));
  CHECK(!fs::exists(dir / "bad" / "change-scores.json"));
  // A detection naming an element the before map does not have: exit 3.
  MapChanges ghost = truthChanges(before);
  ghost.changes[0].before->id = 999;
  io::writeMapChanges(dir / "ghost.json", ghost);
  CHECK(run("ghost.json", "ghost") == 3);
  CHECK_THAT(test::readText(dir / "ghost.err"),
             Catch::Contains("ghost.json") && Catch::Contains("changes[0].before_id"));
  CHECK(run("missing.json", "missing") == 4);
  // A truth without changes: a warning by default, exit 3 with --strict.
  MapChanges none;
  none.origin = before.origin;
  io::writeMapChanges(dir / "none.json", none);
  const auto strict = test::runCommand(
      quoted(test::appPath("evaluate")) + " changes -q --strict true --detected " +
      quoted(dir / "truth.json") + " --truth " + quoted(dir / "none.json") + " --before " +
      quoted(dir / "before.json") + " -o " + quoted(dir / "strict") + " >/dev/null 2>&1");
  CHECK(strict == 3);
}
