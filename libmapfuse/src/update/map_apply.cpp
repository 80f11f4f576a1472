#include "mapfuse/update/map_apply.hpp"

#include <string>
#include <unordered_map>

#include "mapfuse/core/error.hpp"

namespace mapfuse::update {

UpdatedMap applyChanges(const VectorMap& map, const MapChanges& changes) {
  std::unordered_map<int64_t, const MapChange*> by_id;
  std::vector<const MapChange*> additions;
  std::unordered_map<int64_t, std::size_t> index;
  for (std::size_t i = 0; i < map.instances.size(); ++i) index[map.instances[i].id] = i;
  for (const MapChange& c : changes.changes) {
    if (c.kind == ChangeKind::kAdded) {
      if (!c.after) throw InputError("an added change without its after state");
      if (index.count(c.after->id))
        throw InputError("an added element takes id " + std::to_string(c.after->id) +
                         ", which the map already has");
      additions.push_back(&c);
      continue;
    }
    if (!c.before || !index.count(c.before->id))
      throw InputError("a " + std::string(changeKindName(c.kind)) +
                       " change names an element the map does not have" +
                       (c.before ? " (id " + std::to_string(c.before->id) + ")" : ""));
    if (c.kind != ChangeKind::kRemoved && !c.after)
      throw InputError("the " + std::string(changeKindName(c.kind)) + " change of element " +
                       std::to_string(c.before->id) + " has no after state");
    if (!by_id.emplace(c.before->id, &c).second)
      throw InputError("element " + std::to_string(c.before->id) + " changes twice");
  }
  UpdatedMap out;
  out.map.origin = map.origin;
  out.map.source = map.source.empty() ? "update" : map.source + ", updated";
  out.map.instances.reserve(map.instances.size() + additions.size());
  for (const MapInstance& m : map.instances) {
    const auto it = by_id.find(m.id);
    if (it == by_id.end()) {
      out.map.instances.push_back(m);
      out.unchanged.push_back(m.id);
      continue;
    }
    const MapChange& c = *it->second;
    if (c.kind == ChangeKind::kRemoved) {
      out.removed.push_back(m.id);
      continue;
    }
    MapInstance after = *c.after;
    after.id = m.id;
    after.version = m.version + 1;
    after.support = m.support;
    after.note = std::string(changeKindName(c.kind)) + " by a map update";
    out.map.instances.push_back(std::move(after));
    out.changed.push_back(m.id);
  }
  for (const MapChange* c : additions) {
    MapInstance after = *c->after;
    after.version = 1;
    after.support.drives = int(c->supporting_traversals.size());
    after.note = "added by a map update";
    out.added.push_back(after.id);
    out.map.instances.push_back(std::move(after));
  }
  return out;
}

}  // namespace mapfuse::update
