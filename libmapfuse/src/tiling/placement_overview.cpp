#include "mapfuse/tiling/placement_overview.hpp"

#include <algorithm>

namespace mapfuse::tiling {

PlacementOverview overviewOfShifts(const std::map<GroupKey, Eigen::Vector3d>& shifts,
                                   const std::map<GroupKey, int>& group_size, std::size_t count) {
  PlacementOverview o;
  auto groupShift = [&](const GroupKey& key) {
    const auto n = group_size.find(key);
    return GroupShift{key, n == group_size.end() ? 0 : n->second, shifts.at(key)};
  };
  std::vector<std::pair<double, GroupKey>> moved;
  for (const auto& [key, s] : shifts) moved.emplace_back(s.head<2>().norm(), key);
  std::sort(moved.rbegin(), moved.rend());
  for (std::size_t i = 0; i < std::min(count, moved.size()); ++i)
    o.largest_shifts.push_back(groupShift(moved[i].second));

  std::map<std::string, TileShift> tiles;
  for (const auto& [key, n] : group_size) {
    o.single_piece_groups += n == 1;
    TileShift& t = tiles[key.tile.name()];
    t.tile = key.tile.name();
    ++t.groups;
    if (n > t.largest.pieces) t.largest = groupShift(key);
  }
  for (auto& [name, t] : tiles) o.per_tile.push_back(t);
  return o;
}

}  // namespace mapfuse::tiling
