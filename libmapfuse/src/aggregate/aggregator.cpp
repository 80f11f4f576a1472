#include "mapfuse/aggregate/aggregator.hpp"

#include <cmath>
#include <map>
#include <set>

#include "bezier_fit.hpp"
#include "discrete_merge.hpp"
#include "grid_instances.hpp"
#include "lane_instantiation.hpp"

namespace mapfuse::aggregate {
namespace {

MapInstance vectorizeLane(const ObservationSet& set, const LaneInstance& lane,
                          const AggregatorParams& params, AggregatorStats& stats, double& sum_sq,
                          std::size_t& count) {
  MapInstance inst = fittedLaneLine(lane.centreline, params, stats, sum_sq, count);
  // dashed/solid and colour by (confidence-weighted) majority vote
  std::map<LineStyle, double> styles;
  std::map<LineColor, double> colors;
  std::set<int> drives;
  for (std::size_t i : lane.observations) {
    const Observation& o = set.items[i];
    styles[o.attributes.style] += o.confidence;
    colors[o.attributes.color] += o.confidence;
    drives.insert(o.drive);
    inst.support.observations += o.observations;
  }
  double best = -1;
  for (const auto& [s, w] : styles)
    if (w > best) best = w, inst.attributes.style = s;
  best = -1;
  for (const auto& [c, w] : colors)
    if (w > best) best = w, inst.attributes.color = c;
  inst.support.drives = int(drives.size());
  return inst;
}

}  // namespace

VectorMap aggregateObservations(const ObservationSet& set, const AggregatorParams& params,
                                AggregatorStats* stats_out) {
  AggregatorStats stats;
  VectorMap map;
  map.origin = set.origin;
  map.source = "aggregate";
  for (const auto& o : set.items) ++stats.observations[std::size_t(o.cls)];

  const bool grid_vote = params.method == "grid_vote";
  if (grid_vote) {
    // the Qin et al. 2021 baseline: the ground classes by grid voting (grid_vote.hpp)
    for (auto& inst : gridVoteInstances(set.items, params, set.num_drives, stats))
      map.instances.push_back(std::move(inst));
  } else {
    // lane lines: two-stage DBSCAN, then Bezier vectorization
    const auto lane_idx = indicesOfClass(set, CrowdClass::kLaneLine);
    const LaneInstantiation lanes =
        instantiateLanes(set.items, lane_idx, params.lanes, set.num_drives);
    stats.lanes = lanes.stats;
    stats.noise[std::size_t(CrowdClass::kLaneLine)] = lanes.stats.noise_pieces;
    double sum_sq = 0;
    std::size_t count = 0;
    std::vector<MapInstance> lane_instances(lanes.instances.size());
    for (std::size_t i = 0; i < lanes.instances.size(); ++i)
      lane_instances[i] = vectorizeLane(set, lanes.instances[i], params, stats, sum_sq, count);
    stats.bezier_rms_deviation = count ? std::sqrt(sum_sq / double(count)) : 0.0;
    for (auto& inst : lane_instances) map.instances.push_back(std::move(inst));
  }

  // every other class (with grid_vote: the elevated ones): discrete clustering and weighted
  // merging
  for (int c = 0; c < kNumCrowdClasses; ++c) {
    const CrowdClass cls = CrowdClass(c);
    if (cls == CrowdClass::kLaneLine || (grid_vote && isGridClass(cls))) continue;
    const auto idx = indicesOfClass(set, cls);
    if (idx.empty()) continue;
    std::size_t noise = 0;
    auto merged = mergeDiscrete(set.items, idx, cls, params.discrete, set.num_drives,
                                params.lanes.partner_drives, &noise);  // declared once, in lanes
    stats.noise[std::size_t(c)] = noise;
    for (auto& inst : merged) map.instances.push_back(std::move(inst));
  }
  int64_t next_id = 1;
  for (auto& inst : map.instances) {
    inst.id = next_id++;
    ++stats.instances[std::size_t(inst.cls)];
  }
  if (stats_out) *stats_out = stats;
  return map;
}

}  // namespace mapfuse::aggregate
