#include "mapfuse/stages/aggregate.hpp"

#include <chrono>
#include <cmath>
#include <unordered_set>

#include "mapfuse/core/log.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/geojson.hpp"
#include "mapfuse/io/lsm_io.hpp"
#include "mapfuse/io/map_png.hpp"
#include "mapfuse/io/osm_export.hpp"
#include "mapfuse/io/stage_report.hpp"
#include "mapfuse/io/vector_map_io.hpp"

namespace mapfuse::stages {

void AggregateParams::validate() const {
  const char* s = "AggregateParams";
  requireParam(buffer_width > 0, s, "buffer_width", buffer_width, "buffer_width > 0");
  requireParam(min_overlap_ratio > 0 && min_overlap_ratio <= 1, s, "min_overlap_ratio",
               min_overlap_ratio, "0 < min_overlap_ratio <= 1");
  requireParam(lane_min_pts >= 1, s, "lane_min_pts", lane_min_pts, "lane_min_pts >= 1");
  requireParam(tile_size >= 2 * station_step, s, "tile_size", tile_size,
               "tile_size >= 2 * station_step");
  requireParam(station_step > 0, s, "station_step", station_step, "station_step > 0");
  requireParam(link_distance > 0, s, "link_distance", link_distance, "link_distance > 0");
  requireParam(link_lateral > 0, s, "link_lateral", link_lateral, "link_lateral > 0");
  requireParam(link_angle_deg > 0 && link_angle_deg < 90, s, "link_angle_deg", link_angle_deg,
               "0 < link_angle_deg < 90");
  requireParam(link_min_pts >= 1, s, "link_min_pts", link_min_pts, "link_min_pts >= 1");
  requireParam(link_max_pts >= link_min_pts, s, "link_max_pts", link_max_pts,
               "link_max_pts >= link_min_pts");
  requireParam(min_instance_length >= 0, s, "min_instance_length", min_instance_length,
               "min_instance_length >= 0");
  requireParam(max_deviation > 0, s, "max_deviation", max_deviation, "max_deviation > 0");
  requireParam(sample_step > 0, s, "sample_step", sample_step, "sample_step > 0");
  requireParam(min_iou > 0 && min_iou <= 1, s, "min_iou", min_iou, "0 < min_iou <= 1");
  requireParam(sign_radius > 0, s, "sign_radius", sign_radius, "sign_radius > 0");
  requireParam(point_radius > 0, s, "point_radius", point_radius, "point_radius > 0");
  requireParam(stop_line_radius > 0, s, "stop_line_radius", stop_line_radius,
               "stop_line_radius > 0");
  requireParam(discrete_min_pts >= 1, s, "discrete_min_pts", discrete_min_pts,
               "discrete_min_pts >= 1");
  requireParam(coordinate_quantum >= 0, s, "coordinate_quantum", coordinate_quantum,
               "coordinate_quantum >= 0");
  requireParam(png_resolution > 0, s, "png_resolution", png_resolution, "png_resolution > 0");
  requireParam(road_tolerance > 0, s, "road_tolerance", road_tolerance, "road_tolerance > 0");
}

aggregate::AggregatorParams AggregateParams::toAggregator() const {
  aggregate::AggregatorParams p;
  p.lanes.buffer_width = buffer_width;
  p.lanes.min_overlap_ratio = min_overlap_ratio;
  p.lanes.min_pts = lane_min_pts;
  p.lanes.tile_size = tile_size;
  p.lanes.station_step = station_step;
  p.lanes.link_distance = link_distance;
  p.lanes.link_lateral = link_lateral;
  p.lanes.link_angle_deg = link_angle_deg;
  p.lanes.link_min_pts = link_min_pts;
  p.lanes.link_max_pts = link_max_pts;
  p.lanes.min_instance_length = min_instance_length;
  p.bezier.max_deviation = max_deviation;
  p.sample_step = sample_step;
  p.discrete.min_iou = min_iou;
  p.discrete.sign_radius = sign_radius;
  p.discrete.point_radius = point_radius;
  p.discrete.stop_line_radius = stop_line_radius;
  p.discrete.min_pts = discrete_min_pts;
  return p;
}

double coveredRoadKm(const std::vector<Lsm>& lsms, double tolerance) {
  auto key = [&](const Eigen::Vector3d& p) {
    return (int64_t(std::floor(p.x() / tolerance)) << 32) ^
           (int64_t(std::floor(p.y() / tolerance)) & 0xffffffffLL);
  };
  std::unordered_multimap<int64_t, Eigen::Vector3d> accepted;
  double metres = 0.0;
  for (const Lsm& lsm : lsms) {
    std::vector<Eigen::Vector3d> samples;
    for (std::size_t i = 1; i < lsm.keyframes.size(); ++i) {
      const Eigen::Vector3d a = lsm.keyframes[i - 1].T_frame_body.translation();
      const Eigen::Vector3d b = lsm.keyframes[i].T_frame_body.translation();
      const int n = std::max(1, int(std::ceil((b - a).norm())));
      for (int k = 0; k < n; ++k) samples.push_back(a + (b - a) * (double(k) + 0.5) / n);
      const double step = (b - a).norm() / n;
      for (int k = 0; k < n; ++k) {
        const Eigen::Vector3d& s = samples[samples.size() - n + k];
        bool known = false;
        const int64_t ix = int64_t(std::floor(s.x() / tolerance));
        const int64_t iy = int64_t(std::floor(s.y() / tolerance));
        for (int64_t dx = -1; dx <= 1 && !known; ++dx)
          for (int64_t dy = -1; dy <= 1 && !known; ++dy) {
            auto range = accepted.equal_range(((ix + dx) << 32) ^ ((iy + dy) & 0xffffffffLL));
            for (auto it = range.first; it != range.second && !known; ++it)
              known = (it->second - s).head<2>().norm() <= tolerance;
          }
        if (!known) metres += step;
      }
    }
    for (const auto& s : samples) accepted.emplace(key(s), s);
  }
  return metres / 1000.0;
}

nlohmann::json runAggregate(const std::vector<std::string>& inputs,
                            const std::filesystem::path& out_dir, const AggregateParams& params) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  if (inputs.empty()) throw InputError("no input LSM given");
  std::vector<Lsm> lsms;
  for (const auto& f : inputs) lsms.push_back(io::readLsm(f));
  const auto set = aggregate::collectObservations(lsms, inputs);
  const auto t1 = Clock::now();
  MAPFUSE_INFO("aggregate: " << set.items.size() << " observations from " << lsms.size()
                             << " drives");

  aggregate::AggregatorStats stats;
  const VectorMap map = aggregate::aggregateObservations(set, params.toAggregator(), &stats);
  const auto t2 = Clock::now();

  // outputs (each written atomically)
  std::filesystem::create_directories(out_dir);
  io::VectorMapWriteOptions compact;
  compact.compact = true;
  compact.coordinate_quantum = params.coordinate_quantum;
  io::writeVectorMap(out_dir / "map.cbor", map, compact);
  io::writeVectorMap(out_dir / "map.json", map);
  io::writeGeoJson(out_dir / "map.geojson", map);
  std::vector<io::DrivePath> drives(lsms.size());  // travel directions of the lanelets
  for (std::size_t d = 0; d < lsms.size(); ++d)
    for (const auto& k : lsms[d].keyframes) drives[d].push_back(k.T_frame_body.translation());
  io::Lanelet2ExportStats osm_stats;
  io::writeOsm(out_dir / "map.osm", map, drives, &osm_stats);
  if (params.write_png) {
    std::vector<std::vector<Eigen::Vector3d>> background;
    background.reserve(set.items.size());
    for (const auto& o : set.items) background.push_back(o.points);
    io::MapPngOptions png;
    png.resolution = params.png_resolution;
    io::writeMapPng(out_dir / "map.png", map, background, png);
  }
  const auto t3 = Clock::now();

  const double cbor_kb = double(std::filesystem::file_size(out_dir / "map.cbor")) / 1024.0;
  const double road_km = coveredRoadKm(lsms, params.road_tolerance);
  const double lane_km = totalLineLength(map, CrowdClass::kLaneLine) / 1000.0;
  nlohmann::json per_class = nlohmann::json::object();
  for (int c = 0; c < kNumCrowdClasses; ++c)
    per_class[crowdClassName(CrowdClass(c))] = {{"observations", stats.observations[c]},
                                                {"instances", stats.instances[c]},
                                                {"noise", stats.noise[c]}};
  auto seconds = [](auto a, auto b) { return std::chrono::duration<double>(b - a).count(); };
  nlohmann::json summary = {
      {"inputs", {{"drives", lsms.size()}, {"observations", set.items.size()}}},
      {"instances", map.instances.size()},
      {"classes", per_class},
      {"lane_instantiation",
       {{"pieces", stats.lanes.pieces},
        {"noise_pieces", stats.lanes.noise_pieces},
        {"fragments", stats.lanes.fragments},
        {"links", stats.lanes.links},
        {"branch_ends", stats.lanes.branch_ends},
        {"dropped_short", stats.lanes.dropped_short}}},
      {"vectorization",
       {{"bezier_segments", stats.bezier_segments},
        {"max_deviation_limit_m", params.max_deviation},
        {"max_deviation_m", stats.bezier_max_deviation},
        {"rms_deviation_m", stats.bezier_rms_deviation}}},
      {"size",
       {{"cbor_kb", cbor_kb},
        {"road_km", road_km},
        {"lane_line_km", lane_km},
        {"kb_per_km", road_km > 0 ? nlohmann::json(cbor_kb / road_km) : nlohmann::json(nullptr)},
        {"target_kb_per_km", 20.0}}},
      {"lanelet2",
       {{"lanelets", osm_stats.lanelets},
        {"lanelets_direction_known", osm_stats.lanelets_direction_known},
        {"connector_lanelets", osm_stats.connector_lanelets},
        {"crosswalk_lanelets", osm_stats.crosswalk_lanelets},
        {"regulatory_elements", osm_stats.regulatory_elements},
        {"lane_line_bound_share",
         osm_stats.lane_line_m > 0 ? osm_stats.bound_m / osm_stats.lane_line_m : 0.0}}},
      {"timings_s",
       {{"read", seconds(t0, t1)}, {"aggregate", seconds(t1, t2)}, {"write", seconds(t2, t3)}}},
      {"converged", true}};
  io::writeResolvedConfig(out_dir, "aggregate", paramsToJson(params));
  io::writeSummary(out_dir, "aggregate", summary);
  MAPFUSE_INFO("aggregate: " << map.instances.size() << " instances, " << cbor_kb << " KB, "
                             << (road_km > 0 ? cbor_kb / road_km : 0.0) << " KB/km");
  return summary;
}

}  // namespace mapfuse::stages
