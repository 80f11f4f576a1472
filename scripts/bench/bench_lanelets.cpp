// How much of the procedural world's lanes the Lanelet2 export of an aggregated map covers with
// lanelets (both bounds), and in which direction (docs/performance-lanelets.md): rebuilds the
// world `simulate` drove on (default procedural parameters, its seed), reads the exported
// map.osm with the project's Lanelet2 reader and map.json for the lane lines, and samples every
// true lane every metre (eval/lanelet_coverage.hpp).
//
//   bench_lanelets --seed 42 --osm map.osm --map map.json   -> one JSON line on stdout
#include <CLI/CLI.hpp>
#include <iostream>
#include <nlohmann/json.hpp>

#include "mapfuse/cli/app.hpp"
#include "mapfuse/eval/lanelet_coverage.hpp"
#include "mapfuse/io/lanelet2_osm.hpp"
#include "mapfuse/io/vector_map_io.hpp"
#include "mapfuse/sim/drive.hpp"
#include "mapfuse/sim/procedural_world.hpp"

using namespace mapfuse;

int main(int argc, char** argv) {
  CLI::App app("Lanelet coverage of the true lanes by an exported map.osm", "bench_lanelets");
  uint64_t seed = 42;
  std::string osm_path, map_path;
  geo::GeoOrigin origin{49.0, 8.4, 110.0};  // simulate's default origin
  app.add_option("--seed", seed, "simulate's seed");
  app.add_option("--osm", osm_path, "exported Lanelet2 map")->required();
  app.add_option("--map", map_path, "the same map as mapfuse.vector_map JSON")->required();
  return cli::run(app, argc, argv, [&] {
    // The world exactly as the simulate stage builds it (stages/simulate.cpp).
    const sim::World world =
        sim::buildProceduralWorld(sim::ProceduralParams{}, origin, sim::deriveSeed(seed, 1000001));
    const io::Lanelet2Map osm = io::readLanelet2Osm(osm_path);
    const auto shapes = eval::laneletShapes(osm, origin);
    // The map's lane lines in the world's ENU (the chain's origin differs).
    VectorMap map = io::readVectorMap(map_path);
    const geo::EnuConverter from(map.origin), to(origin);
    for (auto& m : map.instances)
      for (auto& p : m.points) p = to.toEnu(from.toWgs84(p));
    std::vector<eval::TrueLane> lanes;
    for (const auto& l : world.lanes) lanes.push_back({l.centerline, l.width});
    const eval::LaneletCoverage c = eval::measureLaneletCoverage(lanes, map, shapes);
    int one_way = 0;
    for (const auto& s : shapes) one_way += s.one_way;
    std::cout << nlohmann::json{{"lanelets", shapes.size()},
                                {"lanelets_one_way", one_way},
                                {"true_lane_m", c.lane_m},
                                {"marked_m", c.marked_m},
                                {"covered_m", c.covered_m},
                                {"directed_m", c.directed_m},
                                {"reversed_m", c.reversed_m},
                                {"share", c.share()},
                                {"directed_share", c.directedShare()}}
                     .dump()
              << "\n";
  });
}
