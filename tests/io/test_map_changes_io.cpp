// Map change files (docs/formats.md "Map changes"): a round trip keeps every field; each
// malformed field is refused naming the file and the field; the GeoJSON export draws each state.
#include <catch2/catch.hpp>

#include "mapfuse/io/map_changes_io.hpp"
#include "support/error_matchers.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;

namespace {

MapInstance element(int64_t id, CrowdClass cls, std::vector<Eigen::Vector3d> points) {
  MapInstance m;
  m.id = id;
  m.cls = cls;
  m.points = std::move(points);
  return m;
}

MapChanges sample() {
  MapChanges c;
  c.origin = {49.0110, 8.4228, 112.8};
  c.source = "test";
  MapChange removed{ChangeKind::kRemoved, CrowdClass::kPole, {}, {}, {}, {}};
  removed.before = element(7, CrowdClass::kPole, {{1.0, 2.0, 0.0}});
  removed.before->height = 6.5;
  MapChange moved{ChangeKind::kMoved, CrowdClass::kTrafficSign, {}, {}, 0.8, {"veh00_trav001"}};
  moved.before =
      element(9, CrowdClass::kTrafficSign, {{0, 0, 2}, {0.6, 0, 2}, {0.6, 0, 2.6}, {0, 0, 2.6}});
  moved.after = moved.before;
  for (auto& p : moved.after->points) p.x() += 2.5;
  MapChange retyped{ChangeKind::kRetyped, CrowdClass::kLaneLine, {}, {}, {}, {}};
  retyped.before = element(3, CrowdClass::kLaneLine, {{0, 0, 0}, {30, 0, 0}});
  retyped.before->attributes = {LineStyle::kDashed, LineColor::kWhite};
  retyped.after = retyped.before;
  retyped.after->attributes.style = LineStyle::kSolid;
  MapChange added{ChangeKind::kAdded, CrowdClass::kStopLine, {}, {}, 0.55, {"a", "b"}};
  added.after = element(100, CrowdClass::kStopLine, {{10, -1.75, 0}, {10, 1.75, 0}});
  c.changes = {removed, moved, retyped, added};
  return c;
}

/// The sample as JSON with one edit, parsed: the ParseError it raises.
void checkRefused(const std::function<void(io::Json&)>& edit, const std::string& field,
                  const std::string& problem) {
  io::Json doc = io::mapChangesToJson(sample());
  edit(doc);
  CHECK_THROWS_MATCHES(io::mapChangesFromJson(doc, "c.json"), ParseError,
                       test::ParseErrorAt(field, "c.json", problem));
}

}  // namespace

TEST_CASE("map changes round trip through JSON and CBOR", "[io]") {
  const MapChanges in = sample();
  const auto dir = test::tempDir("map_changes_io");
  for (const char* name : {"c.json", "c.cbor"}) {
    io::writeMapChanges(dir / name, in);
    const MapChanges out = io::readMapChanges(dir / name);
    CHECK(out.source == "test");
    CHECK(out.origin.lat == in.origin.lat);
    REQUIRE(out.changes.size() == in.changes.size());
    for (std::size_t i = 0; i < in.changes.size(); ++i) {
      const MapChange &a = in.changes[i], &b = out.changes[i];
      CHECK(a.kind == b.kind);
      CHECK(a.cls == b.cls);
      CHECK(a.confidence == b.confidence);
      CHECK(a.supporting_traversals == b.supporting_traversals);
      REQUIRE(a.before.has_value() == b.before.has_value());
      REQUIRE(a.after.has_value() == b.after.has_value());
      for (const auto& [x, y] : {std::pair{a.before, b.before}, std::pair{a.after, b.after}}) {
        if (!x) continue;
        CHECK(x->id == y->id);
        CHECK(x->points == y->points);
        CHECK(x->height == y->height);
        CHECK(x->attributes == y->attributes);
      }
    }
  }
}

TEST_CASE("malformed map changes are refused naming the field", "[io]") {
  using io::Json;
  checkRefused([](Json& d) { d["format"] = "mapfuse.vector_map"; }, "format", "expected");
  checkRefused([](Json& d) { d["changes"][0]["kind"] = "vanished"; }, "changes[0].kind",
               "unknown change kind");
  checkRefused([](Json& d) { d["changes"][0]["class"] = "tree"; }, "changes[0].class",
               "unknown class");
  checkRefused([](Json& d) { d["changes"][0]["after_id"] = 8; }, "changes[0].after_id",
               "no after state");
  checkRefused([](Json& d) { d["changes"][1].erase("before"); }, "changes[1].before", "");
  checkRefused([](Json& d) { d["changes"][3].erase("after_id"); }, "changes[3].after_id", "");
  checkRefused([](Json& d) { d["changes"][3]["before_id"] = 4; }, "changes[3].before_id",
               "no before state");
  checkRefused(
      [](Json& d) {
        d["changes"][0]["before"]["points"].push_back({0, 0, 0});
      },
      "changes[0].before.points", "exactly 1 point");
  checkRefused([](Json& d) { d["changes"][2]["after"]["points"].erase(1); },
               "changes[2].after.points", "at least 2 points");
  checkRefused([](Json& d) { d["changes"][1]["confidence"] = 1.5; }, "changes[1].confidence", "");
  checkRefused([](Json& d) { d["changes"][1]["supporting_traversals"] = 3; },
               "changes[1].supporting_traversals", "");
  checkRefused([](Json& d) { d["changes"][2]["before_id"] = 7; }, "changes[2].before_id",
               "appears in two changes");
  checkRefused([](Json& d) { d["changes"][2]["after"]["style"] = "wavy"; },
               "changes[2].after.style", "unknown line style");
  checkRefused([](Json& d) { d["changes"][0]["why"] = "x"; }, "changes[0].why", "");
}

TEST_CASE("the change GeoJSON draws each state of each change", "[io]") {
  const io::Json g = io::mapChangesToGeoJson(sample());
  const io::Json& f = g["features"];
  REQUIRE(f.size() == 6);  // removed: before; moved, retyped: both; added: after
  CHECK(f[0]["properties"]["kind"] == "removed");
  CHECK(f[0]["properties"]["state"] == "before");
  CHECK(f[0]["properties"]["before_id"] == 7);
  CHECK(f[1]["properties"]["state"] == "before");
  CHECK(f[2]["properties"]["state"] == "after");
  CHECK(f[2]["properties"]["change"] == 1);
  CHECK(f[2]["properties"]["confidence"] == 0.8);
  CHECK(f[2]["properties"]["supporting_traversals"] == 1);
  CHECK(f[4]["properties"]["style"] == "solid");
  CHECK(f[5]["properties"]["traversal_ids"] == "a,b");
  CHECK(f[5]["geometry"]["type"] == "LineString");
  CHECK(f[0]["geometry"]["type"] == "Point");
}
