#include "mapfuse/tiling/tile_pieces.hpp"

#include "mapfuse/core/error.hpp"

namespace mapfuse::tiling {

std::vector<MeasuredPiece> measureTilePieces(const io::TilesManifestTile& tile,
                                             const io::TileAlignment& t,
                                             const PieceLinkSettings& settings) {
  auto links = t.kept;
  const auto agreeing = agreeingPieces(t.aligned, settings.link_distance, settings.link_min_points);
  links.insert(links.end(), agreeing.begin(), agreeing.end());
  const std::vector<int> group = registrationGroups(int(t.inputs.size()), links);
  std::vector<MeasuredPiece> out;
  for (std::size_t i = 0; i < t.inputs.size(); ++i) {
    MeasuredPiece f{
        {{tile.ix, tile.iy}, group[i]}, tile.name, t.input_files[i], t.aligned_files[i], {}};
    try {
      f.piece = measurePiece(t.inputs[i], t.aligned[i]);
    } catch (const InputError& e) {
      throw InputError(f.aligned.string() + ": " + e.what());
    }
    f.piece.group = f.group;
    out.push_back(std::move(f));
  }
  return out;
}

}  // namespace mapfuse::tiling
