#pragma once
/// @file Stage `balance`: places the independently aligned tiles of a tiled run consistently
/// (tiling/placement.hpp) before they are aggregated.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "mapfuse/tiling/placement.hpp"

namespace mapfuse::stages {

struct BalanceParams {
  tiling::PlacementParams placement;
  std::string aligned_subdir = "align";  ///< per tile folder: where align wrote its output
  double link_distance = 0.3;            ///< m: element points of two pieces this close coincide
  int link_min_points = 10;              ///< coinciding points that make two pieces one group

  template <class V>
  void visit(V& v) {
    placement.visit(v);
    v("link_distance", link_distance, "m",
      "element points of two aligned pieces this close coincide (tiling/piece_links.hpp)");
    v("link_min_points", link_min_points, "",
      "coinciding element points that put two pieces of a tile in one group");
    v("aligned_subdir", aligned_subdir, "",
      "folder, inside each tile folder, holding align's output and align.summary.json");
  }
  void validate() const;
};

/// @brief Reads tiles.json (written by `tile`), every tile's input LSMs and, from
/// <tile>/<aligned_subdir>/, align's output LSMs and align.summary.json. A tile's groups join
/// the pieces linked by a registration its pose graph kept or whose elements coincide after
/// alignment (GBA ties pieces too); solves the placement and writes each aligned LSM moved
/// by its group's shift to <out>/<tile>/<file name>, plus balance.config.json and
/// balance.summary.json in <out>. @return the summary.
/// @throws InputError when a tile's align output is missing or does not match its inputs,
/// ParseError on a malformed tiles.json or align summary.
nlohmann::json runBalance(const std::filesystem::path& tiles_json, const std::filesystem::path& out,
                          const BalanceParams& params);

}  // namespace mapfuse::stages
