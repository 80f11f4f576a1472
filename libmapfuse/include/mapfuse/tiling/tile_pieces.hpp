#pragma once
/// @file What align did to each piece of one tile, for balance (docs/tiling.md): the tile's
/// registration groups (align's kept links plus pieces that agree after alignment) and, per
/// piece, its measured move (measurePiece).
#include <filesystem>
#include <string>
#include <vector>

#include "mapfuse/io/tile_alignment.hpp"
#include "mapfuse/io/tiles_manifest.hpp"
#include "mapfuse/tiling/piece_links.hpp"
#include "mapfuse/tiling/placement.hpp"

namespace mapfuse::tiling {

/// One tile input: the georef piece `tile` wrote, align's output for it, its group and move.
struct MeasuredPiece {
  GroupKey group;
  std::string tile_name;
  std::filesystem::path input, aligned;
  TilePiece piece;
};

/// @brief The pieces of `tile` (read into `alignment`), in groups, with what align did to each.
/// @throws InputError naming the aligned file of a piece that cannot be measured.
std::vector<MeasuredPiece> measureTilePieces(const io::TilesManifestTile& tile,
                                             const io::TileAlignment& alignment,
                                             const PieceLinkSettings& links);

}  // namespace mapfuse::tiling
