// stitch with its inputs (docs/formats.md "Tiled runs"): tiles.json and one vector map per
// tile, as parts of one input separated by lines "====" (part 0 tiles.json; part i the map of
// the i-th tile in the manifest's order, JSON when it starts with '{', else CBOR; an empty part
// is a tile without its map). The parts become <scratch>/stitch/tiles.json and
// <scratch>/stitch/<tile>/map.{json,cbor}, and the stage runs whole (stages::runStitch: manifest,
// tile of each map, the maps, the stitching, the outputs). Refusals: exit 3 for bad data, 2 for
// a set of maps that does not match the manifest. What stitch writes must read back.
#include "fuzz_support.hpp"
#include "fuzz_world.hpp"
#include "mapfuse/io/tiles_manifest.hpp"
#include "mapfuse/stages/stitch.hpp"

using namespace mapfuse;
namespace fs = std::filesystem;

namespace {
constexpr std::size_t kMaxTiles = 8;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const auto parts = fuzz::splitParts(fuzz::bytesOf(data, size), 1 + kMaxTiles, /*binary=*/true);
  const fs::path dir = fuzz::scratchDir() / "stitch";
  fs::remove_all(dir);
  fs::create_directories(dir);
  fuzz::writeFile(dir / "tiles.json", parts[0]);
  // The tile folders come from the manifest: read it first (refusals are the stage's own).
  io::TilesManifest manifest;
  if (!fuzz::accepts([&] { manifest = io::readTilesManifest(dir / "tiles.json"); })) return 0;
  std::vector<std::string> maps;
  for (std::size_t i = 0; i < manifest.tiles.size() && i + 1 < parts.size(); ++i) {
    const std::string& bytes = parts[i + 1];
    if (bytes.empty()) continue;
    const fs::path map =
        dir / manifest.tiles[i].name / (bytes.front() == '{' ? "map.json" : "map.cbor");
    fs::create_directories(map.parent_path());
    fuzz::writeFile(map, bytes);
    maps.push_back(map.string());
  }
  VectorMap stitched;
  if (!fuzz::accepts(
          [&] {
            stitched = stages::runStitch(dir / "tiles.json", maps, dir / "out" / "map.cbor",
                                         tiling::StitchParams{});
          },
          {ExitCode::kBadInput, ExitCode::kUsage}))
    return 0;
  MAPFUSE_FUZZ_CHECK(maps.size() == manifest.tiles.size());
  const VectorMap back = io::readVectorMap(dir / "out" / "map.cbor");
  MAPFUSE_FUZZ_CHECK(back.instances.size() == stitched.instances.size());
  for (const auto& inst : back.instances)
    for (const auto& p : inst.points)
      MAPFUSE_FUZZ_CHECK(p.cwiseAbs().maxCoeff() <= io::bounds::kMaxCoordinate + 1.0);
  return 0;
}
