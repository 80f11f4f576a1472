#include "mapfuse/stages/aggregate.hpp"

#include <chrono>
#include <functional>

#include "map_writers.hpp"
#include "mapfuse/cli/params.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/core/parallel_for.hpp"
#include "mapfuse/io/lsm_io.hpp"
#include "mapfuse/io/map_png.hpp"
#include "mapfuse/io/osm_export.hpp"
#include "mapfuse/io/output_transaction.hpp"
#include "mapfuse/io/stage_report.hpp"
#include "mapfuse/io/vector_map_io.hpp"

namespace mapfuse::stages {
namespace {

// The writers of the map in every format (map_writers.hpp), map.png over the observations in
// grey second (after map.osm, the slowest); map.osm's lanelets take their travel direction from
// the drives' keyframe paths. They refer to the arguments (`osm_stats` copied), which must
// outlive them.
std::vector<std::function<void()>> mapWriters(const std::filesystem::path& out_dir,
                                              const VectorMap& map,
                                              const aggregate::ObservationSet& set,
                                              const std::vector<Lsm>& lsms,
                                              const AggregateParams& params,
                                              io::Lanelet2ExportStats* osm_stats) {
  io::VectorMapWriteOptions compact;
  compact.compact = true;
  compact.coordinate_quantum = params.coordinate_quantum;
  auto writers = vectorMapWriters(out_dir, map, lsms, params.lanelet, compact, osm_stats);
  writers.insert(writers.begin() + 1, [&, out_dir] {
    if (!params.write_png) return;
    std::vector<std::vector<Eigen::Vector3d>> background;
    background.reserve(set.items.size());
    for (const auto& o : set.items) background.push_back(o.points);
    io::MapPngOptions png;
    png.resolution = params.png_resolution;
    png.title = "aggregated map (" + std::to_string(lsms.size()) + " drives)";
    io::writeMapPng(out_dir / "map.png", map, background, png);
  });
  return writers;
}

}  // namespace

AggregateRun runAggregate(const std::vector<std::string>& inputs,
                          const std::filesystem::path& out_dir, const AggregateParams& params) {
  using Clock = std::chrono::steady_clock;
  auto seconds = [](auto a, auto b) { return std::chrono::duration<double>(b - a).count(); };
  const auto t0 = Clock::now();
  validateParams(params);
  if (inputs.empty()) throw InputError("no input LSM given");
  io::OutputTransaction outputs(out_dir);  // locked and writable before the work
  std::vector<Lsm> lsms = io::readLsmInputs(inputs, /*covariances=*/false);
  const auto set = aggregate::collectObservations(lsms, inputs);
  // From here on only the trajectories are read (road length, drive directions, pictures): the
  // elements, copied into the observations, are freed before the aggregation's own peak.
  for (Lsm& lsm : lsms) std::vector<Element>().swap(lsm.elements);
  const auto t1 = Clock::now();
  MAPFUSE_INFO("aggregate: " << set.items.size() << " observations from " << lsms.size()
                             << " drives");

  AggregateRun run;
  const VectorMap map = aggregate::aggregateObservations(set, params.aggregator, &run.stats);
  const auto t2 = Clock::now();
  // aggregate's serial tail side by side: the map files and the covered road length (which reads
  // the same trajectories); errors as a serial loop in this order would report them.
  std::filesystem::create_directories(out_dir);
  auto tail = mapWriters(out_dir, map, set, lsms, params, &run.lanelet2);
  tail.emplace_back([&] { run.road_km = aggregate::coveredRoadKm(lsms, params.road); });
  parallelFor(tail.size(), [&](std::size_t i) { tail[i](); });
  const auto t3 = Clock::now();

  run.method = params.aggregator.method;
  run.drives = lsms.size();
  run.observations = set.items.size();
  run.instances = map.instances.size();
  run.max_deviation_limit = params.aggregator.bezier.max_deviation;
  run.cbor_kb = double(std::filesystem::file_size(io::contentPath(out_dir / "map.cbor"))) / 1024.0;
  run.lane_line_km = totalLineLength(map, CrowdClass::kLaneLine) / 1000.0;
  run.seconds_read = seconds(t0, t1);
  run.seconds_aggregate = seconds(t1, t2);
  run.seconds_write = seconds(t2, t3);
  io::writeResolvedConfig(out_dir, "aggregate", paramsToJson(params));
  io::writeSummary(out_dir, "aggregate", toJson(run));
  outputs.commit();
  MAPFUSE_INFO("aggregate: " << map.instances.size() << " instances, " << run.cbor_kb << " KB, "
                             << (run.road_km > 0 ? run.cbor_kb / run.road_km : 0.0) << " KB/km");
  return run;
}

}  // namespace mapfuse::stages
