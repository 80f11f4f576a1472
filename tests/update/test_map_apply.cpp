// The updated map of a map update (docs/update.md "The updated map"): unchanged elements as they
// were read, byte for byte in map.json; changed ones with their id and a new version; removed
// ones gone; added ones appended; a change naming an element the map lacks is refused.
#include <catch2/catch.hpp>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/vector_map_io.hpp"
#include "mapfuse/update/map_apply.hpp"

namespace mapfuse {
namespace {

MapInstance pole(int64_t id, double x, double y) {
  MapInstance m;
  m.id = id;
  m.cls = CrowdClass::kPole;
  m.points = {Eigen::Vector3d(x, y, 0.1 * id)};
  m.height = 4;
  m.support = {int(10 + id), int(100 + id)};
  m.source_ids = {id * 7};
  return m;
}

MapChange change(ChangeKind kind, const MapInstance* before, const MapInstance* after) {
  MapChange c;
  c.kind = kind;
  c.cls = CrowdClass::kPole;
  if (before) c.before = *before;
  if (after) c.after = *after;
  c.confidence = 0.9;
  c.supporting_traversals = {"veh00_trav050", "veh01_trav051"};
  return c;
}

VectorMap before() {
  VectorMap map;
  map.origin = {49.0, 8.4, 110.0};
  map.source = "aggregate";
  map.instances = {pole(1, 10.123456789, 3.3), pole(2, 20, 3), pole(3, 30, -3), pole(4, 40, 3)};
  map.instances[3].version = 2;  // changed by an earlier update
  return map;
}

}  // namespace

TEST_CASE("an updated map keeps unchanged elements as read and versions the changed", "[update]") {
  const VectorMap map = before();
  MapInstance moved = map.instances[2];
  moved.points[0].x() += 2.5;
  MapInstance moved_again = map.instances[3];
  moved_again.points[0].y() -= 1.0;
  const MapInstance added = pole(9, 50, 3);
  MapChanges changes;
  changes.origin = map.origin;
  changes.changes = {change(ChangeKind::kRemoved, &map.instances[1], nullptr),
                     change(ChangeKind::kMoved, &map.instances[2], &moved),
                     change(ChangeKind::kMoved, &map.instances[3], &moved_again),
                     change(ChangeKind::kAdded, nullptr, &added)};
  const update::UpdatedMap u = update::applyChanges(map, changes);
  CHECK(u.unchanged == std::vector<int64_t>{1});
  CHECK(u.removed == std::vector<int64_t>{2});
  CHECK(u.changed == std::vector<int64_t>{3, 4});
  CHECK(u.added == std::vector<int64_t>{9});
  REQUIRE(u.map.instances.size() == 4);
  // the unchanged pole: its JSON (what map.json holds) is the input's, byte for byte
  const auto json = [](const MapInstance& m) {
    VectorMap one;
    one.origin = {49.0, 8.4, 110.0};
    one.instances = {m};
    return io::vectorMapToJson(one).dump();
  };
  CHECK(json(u.map.instances[0]) == json(map.instances[0]));
  // a moved pole: same id, the after geometry, version + 1, support of the map kept
  const MapInstance& m3 = u.map.instances[1];
  CHECK(m3.id == 3);
  CHECK(m3.points[0].x() == 32.5);
  CHECK(m3.version == 2);
  CHECK(m3.support.drives == 13);
  CHECK(u.map.instances[2].version == 3);
  // the addition: appended, version 1, supported by the traversals that saw it
  CHECK(u.map.instances[3].id == 9);
  CHECK(u.map.instances[3].version == 1);
  CHECK(u.map.instances[3].support.drives == 2);
  // versions survive a JSON round trip; version 1 is not written (maps before updates)
  const VectorMap back = io::vectorMapFromJson(io::vectorMapToJson(u.map), "updated.json");
  CHECK(back.instances[2].version == 3);
  CHECK_FALSE(io::vectorMapToJson(map)["instances"][0].contains("version"));
}

TEST_CASE("an updated map refuses changes the map cannot take", "[update]") {
  const VectorMap map = before();
  const MapInstance stranger = pole(77, 0, 0);
  MapChanges unknown;
  unknown.changes = {change(ChangeKind::kRemoved, &stranger, nullptr)};
  CHECK_THROWS_AS(update::applyChanges(map, unknown), InputError);
  MapChanges twice;
  twice.changes = {change(ChangeKind::kRemoved, &map.instances[0], nullptr),
                   change(ChangeKind::kMoved, &map.instances[0], &map.instances[0])};
  CHECK_THROWS_AS(update::applyChanges(map, twice), InputError);
  MapChanges clash;  // an addition with an id the map has
  clash.changes = {change(ChangeKind::kAdded, nullptr, &map.instances[1])};
  CHECK_THROWS_AS(update::applyChanges(map, clash), InputError);
}

}  // namespace mapfuse
