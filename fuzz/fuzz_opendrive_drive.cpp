// OpenDRIVE content, the whole path of `simulate --map X.xodr` (docs/formats.md "Map content
// checks"): the file read from disk as simulate reads it (sim::loadMapWorld: reader,
// georeference, world, lane surface, marking check), routes planned over the lane graph and one
// short traversal driven and observed. What simulate would write from it, the truth vector map
// and the traversal's LSM, must read back (fuzz_world.hpp); the drive stays finite and within
// the coordinate bound. fuzz_opendrive covers the reader and the world alone, faster.
#include "fuzz_support.hpp"
#include "fuzz_world.hpp"
#include "mapfuse/sim/crowd.hpp"
#include "mapfuse/sim/map_world.hpp"

using namespace mapfuse;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const std::filesystem::path file = fuzz::scratchDir() / "fuzz.xodr";
  fuzz::writeFile(file, fuzz::bytesOf(data, size));
  geo::GeoOrigin origin{48.0, 11.0, 500.0};
  sim::MapWorldSettings settings;
  settings.allow_no_markings = true;  // drive worlds of signs and poles too
  sim::World world;
  if (!fuzz::accepts([&] { world = sim::loadMapWorld(file.string(), true, settings, &origin); }))
    return 0;
  fuzz::checkTruthReadsBack(world.truth);

  // One traversal of a short route, at simulate's default rates (the route is where the crash
  // of issue 37 was: an empty resampled route of a collapsed geometry).
  sim::CrowdSettings crowd;
  crowd.traversals = 1;
  crowd.vehicles = 1;
  crowd.routes = 1;
  crowd.route_length = 60.0;
  crowd.seed = size;
  sim::Traversal t;
  if (!fuzz::accepts([&] { t = sim::Crowd(world, origin, crowd).traversal(0); })) return 0;
  MAPFUSE_FUZZ_CHECK(!t.drive.truth.empty());
  for (const Pose3& T : t.drive.truth) {
    MAPFUSE_FUZZ_CHECK(T.matrix().allFinite());
    MAPFUSE_FUZZ_CHECK(T.translation().cwiseAbs().maxCoeff() <= io::bounds::kMaxCoordinate);
  }
  MAPFUSE_FUZZ_CHECK(std::isfinite(t.drive.length()));
  fuzz::checkLsmReadsBack(t.observed.lsm);
  return 0;
}
