#pragma once
/// @file Changes between two vector maps (docs/formats.md "Map changes"): what was removed,
/// added, moved, re-striped or re-typed, with the ids of the "before" and "after" maps and both
/// states. The simulator's change truth (`simulate`, truth/changes.json) and the change report of
/// a map update share this type; `evaluate changes` scores one against the other.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mapfuse/core/vector_map.hpp"

namespace mapfuse {

/// What happened to one element.
enum class ChangeKind : uint8_t {
  kRemoved = 0,  ///< in the before map only
  kAdded,        ///< in the after map only
  kMoved,        ///< a pole or sign displaced horizontally
  kRestriped,    ///< a lane line shifted sideways (whole length or a stretch)
  kRetyped,      ///< dashed <-> solid lane line, or a ground arrow pointing the other way
};
constexpr int kNumChangeKinds = 5;

/// @brief "removed", "added", "moved", "restriped", "retyped".
const char* changeKindName(ChangeKind k);
/// @brief Inverse of changeKindName; nullopt for an unknown name.
std::optional<ChangeKind> changeKindFromName(const std::string& name);

/// One change. `before` is absent for kAdded, `after` for kRemoved; every other kind has both.
/// The instances carry the ids of their maps (before->id: id in the before map, after->id: id in
/// the after map), their class (== cls), attributes, points and height.
struct MapChange {
  ChangeKind kind = ChangeKind::kRemoved;
  CrowdClass cls = CrowdClass::kLaneLine;
  std::optional<MapInstance> before, after;
  std::optional<double> confidence;                ///< [0, 1]; detections only
  std::vector<std::string> supporting_traversals;  ///< drive ids; detections only
};

/// The changes of one map, ENU of `origin` (the before map's).
struct MapChanges {
  geo::GeoOrigin origin;
  std::string source;  ///< who made it ("simulate change truth", "update", ...)
  std::vector<MapChange> changes;
};

/// @brief The geometry that shows a change: the after state, the before state of a removal.
const MapInstance& shownState(const MapChange& change);

}  // namespace mapfuse
