#include "mapfuse/io/map_changes_io.hpp"

#include <set>

#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/geojson.hpp"
#include "mapfuse/io/json_geometry.hpp"

namespace mapfuse::io {
namespace {

/// A state as written: points, height (when not 0), style and colour (when set).
Json stateToJson(const MapInstance& inst) {
  Json j = {{"points", pointsToJson(inst.points)}};
  if (inst.height != 0.0) j["height"] = inst.height;
  if (inst.attributes.style != LineStyle::kNone) j["style"] = lineStyleName(inst.attributes.style);
  if (inst.attributes.color != LineColor::kNone) j["color"] = lineColorName(inst.attributes.color);
  return j;
}

Json changeToJson(const MapChange& c) {
  Json j = {{"kind", changeKindName(c.kind)}, {"class", crowdClassName(c.cls)}};
  if (c.before) j["before_id"] = c.before->id;
  if (c.after) j["after_id"] = c.after->id;
  if (c.before) j["before"] = stateToJson(*c.before);
  if (c.after) j["after"] = stateToJson(*c.after);
  if (c.confidence) j["confidence"] = *c.confidence;
  if (!c.supporting_traversals.empty()) j["supporting_traversals"] = c.supporting_traversals;
  return j;
}

/// Checks the number of points a geometry kind needs (io/vector_map_io's rule).
void checkPointCount(const JsonView& points, CrowdClass cls, std::size_t n) {
  const std::string name = crowdClassName(cls);
  switch (geometryKind(cls)) {
    case GeometryKind::kLine:
      if (n < 2) points.fail("a " + name + " needs at least 2 points, found " + std::to_string(n));
      break;
    case GeometryKind::kPlanar:
      if (n < 3) points.fail("a " + name + " needs at least 3 points, found " + std::to_string(n));
      break;
    case GeometryKind::kPoint:
      if (n != 1) points.fail("a " + name + " needs exactly 1 point, found " + std::to_string(n));
      break;
  }
}

MapInstance stateFromJson(const JsonView& v, CrowdClass cls, int64_t id) {
  v.onlyKeys({"points", "height", "style", "color"});
  MapInstance inst;
  inst.id = id;
  inst.cls = cls;
  inst.points = readPoints(v.at("points"));
  checkPointCount(v.at("points"), cls, inst.points.size());
  if (auto h = v.find("height")) inst.height = h->number(0.0, bounds::kMaxElementHeight);
  if (auto s = v.find("style")) {
    const auto style = lineStyleFromName(s->string());
    if (!style) s->fail("unknown line style '" + s->string() + "'");
    inst.attributes.style = *style;
  }
  if (auto s = v.find("color")) {
    const auto color = lineColorFromName(s->string());
    if (!color) s->fail("unknown line colour '" + s->string() + "'");
    inst.attributes.color = *color;
  }
  return inst;
}

/// The state `name` ("before" / "after") with its id `name`_id: required when `needed`, else
/// refused when present.
std::optional<MapInstance> readState(const JsonView& v, const std::string& name, bool needed,
                                     CrowdClass cls, const std::string& kind) {
  const auto id = v.find(name + "_id");
  const auto state = v.find(name);
  if (!needed) {
    if (id) id->fail("a '" + kind + "' change has no " + name + " state");
    if (state) state->fail("a '" + kind + "' change has no " + name + " state");
    return std::nullopt;
  }
  return stateFromJson(v.at(name), cls, v.at(name + "_id").integer());
}

MapChange changeFromJson(const JsonView& v) {
  v.onlyKeys({"kind", "class", "before_id", "after_id", "before", "after", "confidence",
              "supporting_traversals"});
  MapChange c;
  const std::string kind = v.at("kind").string();
  const auto k = changeKindFromName(kind);
  if (!k)
    v.at("kind").fail("unknown change kind '" + kind +
                      "' (removed, added, moved, restriped, retyped)");
  c.kind = *k;
  const std::string cls = v.at("class").string();
  const auto cc = crowdClassFromName(cls);
  if (!cc) v.at("class").fail("unknown class '" + cls + "'");
  c.cls = *cc;
  c.before = readState(v, "before", c.kind != ChangeKind::kAdded, c.cls, kind);
  c.after = readState(v, "after", c.kind != ChangeKind::kRemoved, c.cls, kind);
  if (auto f = v.find("confidence")) c.confidence = f->number(0.0, 1.0);
  if (auto s = v.find("supporting_traversals"))
    for (std::size_t i = 0; i < s->size(); ++i)
      c.supporting_traversals.push_back(s->at(i).string());
  return c;
}

/// Fails at the second change that names the same id of one map.
void checkUniqueIds(const JsonView& list, const std::vector<MapChange>& changes) {
  std::set<int64_t> before, after;
  for (std::size_t i = 0; i < changes.size(); ++i) {
    const MapChange& c = changes[i];
    if (c.before && !before.insert(c.before->id).second)
      list.at(i)
          .at("before_id")
          .fail("before_id " + std::to_string(c.before->id) +
                " appears in two changes (one change per element)");
    if (c.after && !after.insert(c.after->id).second)
      list.at(i)
          .at("after_id")
          .fail("after_id " + std::to_string(c.after->id) +
                " appears in two changes (one change per element)");
  }
}

}  // namespace

Json mapChangesToJson(const MapChanges& changes) {
  Json list = Json::array();
  for (const auto& c : changes.changes) list.push_back(changeToJson(c));
  return {{"format", kMapChangesFormat},
          {"version", kMapChangesVersion},
          {"source", changes.source},
          {"origin", originToJson(changes.origin)},
          {"changes", std::move(list)}};
}

MapChanges mapChangesFromJson(const Json& doc, const std::string& file) {
  const JsonView v(doc, file);
  v.onlyKeys({"format", "version", "source", "origin", "changes"});
  v.checkFormat(kMapChangesFormat, kMapChangesVersion);
  MapChanges out;
  if (auto s = v.find("source")) out.source = s->string();
  out.origin = readOrigin(v.at("origin"));
  const JsonView list = v.at("changes");
  for (std::size_t i = 0; i < list.size(); ++i) out.changes.push_back(changeFromJson(list.at(i)));
  checkUniqueIds(list, out.changes);
  return out;
}

MapChanges readMapChanges(const std::filesystem::path& path) {
  return mapChangesFromJson(readDocument(path), path.string());
}

void writeMapChanges(const std::filesystem::path& path, const MapChanges& changes) {
  writeDocument(path, mapChangesToJson(changes));
}

Json mapChangesToGeoJson(const MapChanges& changes) {
  // Each state becomes an element of one map, drawn by the vector map's GeoJSON writer.
  VectorMap shown;
  shown.origin = changes.origin;
  struct Drawn {
    std::size_t change;
    bool after;
  };
  std::vector<Drawn> drawn;
  for (std::size_t i = 0; i < changes.changes.size(); ++i)
    for (const bool after : {false, true}) {
      const auto& state = after ? changes.changes[i].after : changes.changes[i].before;
      if (!state) continue;
      shown.instances.push_back(*state);
      shown.instances.back().id = int64_t(drawn.size());
      drawn.push_back({i, after});
    }
  Json doc = vectorMapToGeoJson(shown);
  for (std::size_t f = 0; f < drawn.size(); ++f) {
    const MapChange& c = changes.changes[drawn[f].change];
    Json& props = doc["features"][f]["properties"];
    props.erase("support_drives");
    props.erase("support_observations");
    props["id"] = int64_t(f);
    props["change"] = int64_t(drawn[f].change);
    props["state"] = drawn[f].after ? "after" : "before";
    props["kind"] = changeKindName(c.kind);
    if (c.before) props["before_id"] = c.before->id;
    if (c.after) props["after_id"] = c.after->id;
    if (c.confidence) props["confidence"] = *c.confidence;
    if (!c.supporting_traversals.empty()) {
      std::string ids;
      for (const auto& t : c.supporting_traversals) ids += (ids.empty() ? "" : ",") + t;
      props["supporting_traversals"] = c.supporting_traversals.size();
      props["traversal_ids"] = ids;
    }
  }
  return doc;
}

void writeMapChangesGeoJson(const std::filesystem::path& path, const MapChanges& changes) {
  writeBytesAtomic(path, mapChangesToGeoJson(changes).dump() + "\n");
}

}  // namespace mapfuse::io
