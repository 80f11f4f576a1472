#include "mapfuse/core/map_changes.hpp"

#include <array>

namespace mapfuse {
namespace {
constexpr std::array<const char*, kNumChangeKinds> kKindNames{
    {"removed", "added", "moved", "restriped", "retyped"}};
}  // namespace

const char* changeKindName(ChangeKind k) {
  return kKindNames[static_cast<std::size_t>(k)];
}

std::optional<ChangeKind> changeKindFromName(const std::string& name) {
  for (std::size_t i = 0; i < kKindNames.size(); ++i)
    if (name == kKindNames[i]) return static_cast<ChangeKind>(i);
  return std::nullopt;
}

const MapInstance& shownState(const MapChange& change) {
  return change.after ? *change.after : *change.before;
}

}  // namespace mapfuse
