// The summary of aggregate (aggregate.summary.json), from the area's statistics.
#include "mapfuse/stages/aggregate.hpp"

namespace mapfuse::stages {

nlohmann::json toJson(const AggregateRun& run) {
  const auto& stats = run.stats;
  nlohmann::json per_class = nlohmann::json::object();
  for (int c = 0; c < kNumCrowdClasses; ++c)
    per_class[crowdClassName(CrowdClass(c))] = {{"observations", stats.observations[c]},
                                                {"instances", stats.instances[c]},
                                                {"noise", stats.noise[c]}};
  const double kb_per_km = run.road_km > 0 ? run.cbor_kb / run.road_km : 0.0;
  nlohmann::json out = {
      {"method", run.method},
      {"inputs", {{"drives", run.drives}, {"observations", run.observations}}},
      {"instances", run.instances},
      {"classes", per_class},
      {"lane_instantiation",
       {{"pieces", stats.lanes.pieces},
        {"comparisons", stats.lanes.comparisons},
        {"noise_pieces", stats.lanes.noise_pieces},
        {"fragments", stats.lanes.fragments},
        {"links", stats.lanes.links},
        {"branch_ends", stats.lanes.branch_ends},
        {"dropped_short", stats.lanes.dropped_short}}},
      {"vectorization",
       {{"bezier_segments", stats.bezier_segments},
        {"max_deviation_limit_m", run.max_deviation_limit},
        {"max_deviation_m", stats.bezier_max_deviation},
        {"rms_deviation_m", stats.bezier_rms_deviation}}},
      {"size",
       {{"cbor_kb", run.cbor_kb},
        {"road_km", run.road_km},
        {"lane_line_km", run.lane_line_km},
        {"kb_per_km", run.road_km > 0 ? nlohmann::json(kb_per_km) : nlohmann::json(nullptr)},
        {"target_kb_per_km", 20.0}}},
      {"lanelet2",
       {{"lanelets", run.lanelet2.lanelets},
        {"lanelets_direction_known", run.lanelet2.lanelets_direction_known},
        {"lanelets_oriented_by_neighbours", run.lanelet2.lanelets_oriented_by_neighbours},
        {"connector_lanelets", run.lanelet2.connector_lanelets},
        {"crosswalk_lanelets", run.lanelet2.crosswalk_lanelets},
        {"regulatory_elements", run.lanelet2.regulatory_elements},
        {"right_of_way_elements", run.lanelet2.right_of_way_elements},
        {"all_way_stop_elements", run.lanelet2.all_way_stop_elements},
        {"kink_vertices_removed", run.lanelet2.kink_vertices_removed},
        {"line_ends_joined", run.lanelet2.line_ends_joined},
        {"one_sided_connections", run.lanelet2.one_sided_connections},
        {"same_side_lanelets_dropped", run.lanelet2.same_side_lanelets_dropped},
        {"kink_max_deviation_m", run.lanelet2.kink_max_deviation},
        {"lane_line_bound_share",
         run.lanelet2.lane_line_m > 0 ? run.lanelet2.bound_m / run.lanelet2.lane_line_m : 0.0}}},
      {"timings_s",
       {{"read", run.seconds_read},
        {"aggregate", run.seconds_aggregate},
        {"write", run.seconds_write}}},
      {"converged", true}};
  if (run.method == "grid_vote") {
    const auto& g = stats.grid;
    nlohmann::json won = nlohmann::json::object();
    for (int c = 0; c < kNumCrowdClasses; ++c)
      if (g.class_cells[c] > 0) won[crowdClassName(CrowdClass(c))] = g.class_cells[c];
    out["grid_vote"] = {{"cells", g.cells},
                        {"votes", g.painted},
                        {"voted_cells", g.voted_cells},
                        {"conflict_cells", g.conflict_cells},
                        {"min_votes", g.min_votes_used},
                        {"cells_per_class", won}};
  }
  return out;
}

}  // namespace mapfuse::stages
