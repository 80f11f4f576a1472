// tiles.json (docs/formats.md "Tiled runs"), read by balance and stitch.
#include <set>

#include "fuzz_support.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/tiles_manifest.hpp"
#include "mapfuse/tiling/tile_grid.hpp"

using namespace mapfuse;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const std::string bytes = fuzz::bytesOf(data, size);
  io::TilesManifest m;
  if (!fuzz::accepts([&] {
        m = io::tilesManifestFromJson(io::parseDocument(bytes, io::Encoding::kJson, "tiles.json"),
                                      "tiles.json");
      }))
    return 0;
  // What balance and stitch do with it: a tile grid, each tile's core and folder.
  const tiling::TileGrid grid(m.tile_size, m.margin);
  std::set<std::string> names;
  for (const auto& t : m.tiles) {
    const tiling::Rect core = grid.core({t.ix, t.iy});
    MAPFUSE_FUZZ_CHECK(std::isfinite(core.min_x) && std::isfinite(core.max_y));
    MAPFUSE_FUZZ_CHECK(names.insert(t.name).second);
    for (const auto& f : t.lsms) {
      const std::filesystem::path p = std::filesystem::path("tiles") / t.name / f;
      MAPFUSE_FUZZ_CHECK(p.lexically_normal().string().rfind("tiles/", 0) == 0);
    }
  }
  return 0;
}
