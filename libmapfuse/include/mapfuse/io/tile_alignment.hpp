#pragma once
/// @file What align left in one tile of a tiled run (docs/scaling.md): the georef pieces `tile`
/// wrote, align's output for each (same file name in <tile>/<aligned_subdir>/) and the
/// registrations its pose graph kept (align.summary.json there).
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "mapfuse/core/lsm.hpp"
#include "mapfuse/io/tiles_manifest.hpp"

namespace mapfuse::io {

struct TileAlignment {
  std::vector<std::filesystem::path> input_files, aligned_files;  ///< per piece
  std::vector<Lsm> inputs, aligned;                               ///< per piece
  std::vector<std::pair<int, int>> kept;  ///< registrations align kept, as piece indices
};

/// @brief Reads one tile's pieces and align's output for them.
/// @throws InputError naming the file when align's summary or output for a piece is missing
/// (align the tile again); IoError / ParseError from the readers.
TileAlignment readTileAlignment(const TilesManifestTile& tile,
                                const std::filesystem::path& tiles_dir,
                                const std::string& aligned_subdir);

}  // namespace mapfuse::io
