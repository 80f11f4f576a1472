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

namespace {

nlohmann::json toJson(const Eigen::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}

nlohmann::json toJson(const std::vector<GroupShift>& groups) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& g : groups)
    out.push_back({{"tile", g.group.tile.name()},
                   {"group", g.group.group},
                   {"pieces", g.pieces},
                   {"shift_m", toJson(g.shift)}});
  return out;
}

nlohmann::json toJson(const std::vector<TileShift>& tiles) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& t : tiles)
    out[t.tile] = {{"groups", t.groups},
                   {"largest_group_pieces", t.largest.pieces},
                   {"largest_group_shift_m", toJson(t.largest.shift)}};
  return out;
}

}  // namespace

nlohmann::json placementSummary(const PlacementReport& report, const PlacementOverview& overview) {
  return {{"tiles", report.tiles},
          {"groups", report.groups},
          {"single_piece_groups", overview.single_piece_groups},
          {"pieces", report.pieces},
          {"drives", report.drives},
          {"keyframes", report.keyframes},
          {"downweighted_pieces", report.downweighted},
          {"rms_residual_m", report.rms_residual},
          {"max_shift_m", report.max_shift},
          {"largest_shifts", toJson(overview.largest_shifts)},
          {"per_tile", toJson(overview.per_tile)}};
}

}  // namespace mapfuse::tiling
