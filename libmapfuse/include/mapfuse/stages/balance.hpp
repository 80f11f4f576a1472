#pragma once
/// @file Stage `balance`: places the independently aligned tiles of a tiled run consistently
/// (tiling/placement.hpp) before they are aggregated.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "mapfuse/tiling/piece_links.hpp"
#include "mapfuse/tiling/placement.hpp"

namespace mapfuse::stages {

struct BalanceParams {
  static constexpr const char* kName = "BalanceParams";
  tiling::PlacementParams placement;
  tiling::PieceLinkSettings links;
  std::string aligned_subdir = "align";  ///< per tile folder: where align wrote its output

  template <class V>
  void visit(V& v) {
    placement.visit(v);
    links.visit(v);
    v("aligned_subdir", aligned_subdir, "",
      "folder, inside each tile folder, holding align's output and align.summary.json",
      param::TextRule{[](const std::string& s) { return !s.empty(); }, "not empty"});
  }
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
