#include "mapfuse/io/tile_alignment.hpp"

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/align_registrations.hpp"
#include "mapfuse/io/lsm_io.hpp"

namespace mapfuse::io {

namespace fs = std::filesystem;

TileAlignment readTileAlignment(const TilesManifestTile& tile, const fs::path& tiles_dir,
                                const std::string& aligned_subdir) {
  const fs::path align_dir = tiles_dir / tile.name / aligned_subdir;
  const fs::path summary = align_dir / "align.summary.json";
  if (!fs::exists(summary))
    throw InputError(summary.string() + ": missing; run align on tile " + tile.name +
                     " first (balance needs every tile's align output)");
  TileAlignment t;
  for (const std::string& lsm : tile.lsms) {
    const fs::path input = tiles_dir / lsm;
    const fs::path aligned = align_dir / input.filename();
    if (!fs::exists(aligned))
      throw InputError(aligned.string() + ": align's output for " + input.string() +
                       " is missing (align tile " + tile.name + " again)");
    t.inputs.push_back(readLsm(input));
    t.aligned.push_back(readLsm(aligned));
    t.input_files.push_back(input);
    t.aligned_files.push_back(aligned);
  }
  t.kept = keptPairsAmong(readAlignRegistrations(summary), t.input_files);
  return t;
}

}  // namespace mapfuse::io
