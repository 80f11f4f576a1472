#include "grid_instances.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "bezier_fit.hpp"
#include "lane_fragments.hpp"
#include "lane_links.hpp"
#include "mapfuse/aggregate/geometry2d.hpp"
#include "mapfuse/core/area_outline.hpp"
#include "mapfuse/core/union_find.hpp"

namespace mapfuse::aggregate {
namespace {

using Vec3 = Eigen::Vector3d;

// 8-connected components of the cells `keys` (sorted, so the result is deterministic); with
// tile > 0 only cells whose centres lie in the same square tile of that size connect.
std::vector<std::vector<int64_t>> components(const std::vector<int64_t>& keys, double cell,
                                             double tile) {
  std::unordered_map<int64_t, int> index;
  index.reserve(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) index[keys[i]] = int(i);
  std::vector<int> parent(keys.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto tileOf = [&](int64_t i) {
    return tile > 0 ? std::floor((double(i) + 0.5) * cell / tile) : 0;
  };
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const int64_t ix = VoteGrid::ix(keys[i]), iy = VoteGrid::iy(keys[i]);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy) {
        if ((dx == 0 && dy == 0) || tileOf(ix + dx) != tileOf(ix) || tileOf(iy + dy) != tileOf(iy))
          continue;
        const auto it = index.find(VoteGrid::key(ix + dx, iy + dy));
        if (it != index.end()) parent[findRoot(parent, it->second)] = findRoot(parent, int(i));
      }
  }
  std::vector<std::vector<int64_t>> out;
  std::vector<int> slot(keys.size(), -1);
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const int r = findRoot(parent, int(i));
    if (slot[std::size_t(r)] < 0) {
      slot[std::size_t(r)] = int(out.size());
      out.emplace_back();
    }
    out[std::size_t(slot[std::size_t(r)])].push_back(keys[i]);
  }
  return out;
}

// What the cells of one component add up to.
struct ComponentVotes {
  std::array<double, 3> style{}, color{};
  int max_votes = 0;  ///< of the component's class, over its cells
};

ComponentVotes sumVotes(const VoteGrid& grid, const std::vector<int64_t>& cells, CrowdClass cls) {
  ComponentVotes s;
  for (int64_t k : cells) {
    const GridCell& c = grid.cells().at(k);
    for (int j = 0; j < 3; ++j) s.style[std::size_t(j)] += c.style[std::size_t(j)];
    for (int j = 0; j < 3; ++j) s.color[std::size_t(j)] += c.color[std::size_t(j)];
    s.max_votes = std::max(s.max_votes, int(c.votes[std::size_t(cls)]));
  }
  return s;
}

template <std::size_t N>
std::size_t argmax(const std::array<double, N>& a) {
  return std::size_t(std::max_element(a.begin(), a.end()) - a.begin());
}

std::vector<Vec3> centres(const VoteGrid& grid, const std::vector<int64_t>& cells) {
  std::vector<Vec3> pts;
  pts.reserve(cells.size());
  for (int64_t k : cells) pts.push_back(grid.centre(k));
  return pts;
}

// Lane lines: components cut at the lane tiling -> fragments -> stage-2 links -> Bezier chains.
std::vector<MapInstance> laneInstances(const VoteGrid& grid, const std::vector<int64_t>& cells,
                                       const AggregatorParams& params, AggregatorStats& stats) {
  const auto comps = components(cells, grid.cellSize(), params.lanes.tile_size);
  std::vector<Fragment> frags(comps.size());
  std::vector<ComponentVotes> votes(comps.size());
  for (std::size_t i = 0; i < comps.size(); ++i) {
    frags[i].samples = centres(grid, comps[i]);
    frags[i].centreline = binnedCentreline(frags[i].samples, params.lanes.station_step);
    frags[i].obs = {i};  // the components a fragment pools, for the attribute votes
    votes[i] = sumVotes(grid, comps[i], CrowdClass::kLaneLine);
  }
  mergeSideBySide(frags, params.lanes);
  absorbStubs(frags, params.lanes);
  stats.lanes.fragments = frags.size();
  const FragmentEnds ends(frags, params.lanes);
  std::vector<std::vector<std::size_t>> candidates(ends.size());
  for (std::size_t e = 0; e < ends.size(); ++e) candidates[e] = ends.candidates(e);
  const std::vector<long> link = linkEnds(candidates, params.lanes, stats.lanes);
  const auto lanes = chainFragments(frags, ends, link, params.lanes, stats.lanes);

  std::vector<MapInstance> out;
  double sum_sq = 0;
  std::size_t count = 0;
  for (const LaneInstance& lane : lanes) {
    MapInstance inst = fittedLaneLine(lane.centreline, params, stats, sum_sq, count);
    ComponentVotes sum;
    for (std::size_t c : lane.observations) {  // component indices (frags[i].obs above)
      for (std::size_t j = 0; j < 3; ++j) sum.style[j] += votes[c].style[j];
      for (std::size_t j = 0; j < 3; ++j) sum.color[j] += votes[c].color[j];
      sum.max_votes = std::max(sum.max_votes, votes[c].max_votes);
    }
    inst.attributes.style = LineStyle(argmax(sum.style));
    inst.attributes.color = LineColor(argmax(sum.color));
    inst.support.drives = sum.max_votes;  // one vote per observation: at most the drives
    inst.support.observations = sum.max_votes;
    out.push_back(std::move(inst));
  }
  stats.bezier_rms_deviation = count ? std::sqrt(sum_sq / double(count)) : 0.0;
  return out;
}

// Stop lines, arrows, crosswalks: one instance per component.
std::vector<MapInstance> discreteInstances(const VoteGrid& grid, const std::vector<int64_t>& cells,
                                           CrowdClass cls) {
  const double h = 0.5 * grid.cellSize();
  std::vector<MapInstance> out;
  for (const auto& comp : components(cells, grid.cellSize(), 0.0)) {
    if (cls == CrowdClass::kStopLine && comp.size() < 2) continue;  // no direction
    const std::vector<Vec3> pts = centres(grid, comp);
    Vec3 m = Vec3::Zero();
    for (const auto& p : pts) m += p;
    m /= double(pts.size());
    const Eigen::Vector2d u2 = principalAxis2d(pts);
    const Vec3 u(u2.x(), u2.y(), 0), v(-u2.y(), u2.x(), 0);
    double a0 = 1e300, a1 = -1e300, b0 = 1e300, b1 = -1e300;
    for (const auto& p : pts) {
      a0 = std::min(a0, (p - m).dot(u)), a1 = std::max(a1, (p - m).dot(u));
      b0 = std::min(b0, (p - m).dot(v)), b1 = std::max(b1, (p - m).dot(v));
    }
    MapInstance inst;
    inst.cls = cls;
    if (cls == CrowdClass::kStopLine) {
      // the extreme cell centres: a stroke's end cells lie within half a cell of the line's ends
      inst.points = {m + a0 * u, m + a1 * u};
    } else if (cls == CrowdClass::kCrosswalk) {
      // the quadrilateral outline of the cells' union (core/area_outline.hpp): a skewed
      // crosswalk stays a parallelogram
      const double off[4][2] = {{-h, -h}, {h, -h}, {h, h}, {-h, h}};
      std::vector<Vec3> corners;
      for (const auto& p : pts)
        for (const auto& o : off) corners.push_back(p + Vec3(o[0], o[1], 0));
      inst.points = simplifyRing(convexHullXy(corners), 4);
    } else {  // arrows: the cells' union reaches half a cell beyond their centres
      a0 -= h, a1 += h, b0 -= h, b1 += h;
      inst.points = {m + a0 * u + b0 * v, m + a1 * u + b0 * v, m + a1 * u + b1 * v,
                     m + a0 * u + b1 * v};
    }
    const ComponentVotes votes = sumVotes(grid, comp, cls);
    inst.support.drives = votes.max_votes;
    inst.support.observations = votes.max_votes;
    out.push_back(std::move(inst));
  }
  return out;
}

}  // namespace

std::vector<MapInstance> gridVoteInstances(const std::vector<Observation>& items,
                                           const AggregatorParams& params, int num_drives,
                                           AggregatorStats& stats) {
  std::vector<std::size_t> ground;
  for (std::size_t i = 0; i < items.size(); ++i)
    if (isGridClass(items[i].cls)) ground.push_back(i);
  const VoteGrid grid = voteGrid(items, ground, params.grid);
  const int min_votes = std::max(1, std::min(params.grid.min_votes, num_drives));

  // each cell's class: the most votes, at least min_votes
  std::array<std::vector<int64_t>, kNumGridClasses> won;
  GridVoteStats& g = stats.grid;
  g.cells = grid.cells().size();
  g.painted = grid.votes();
  g.min_votes_used = std::size_t(min_votes);
  for (const auto& [k, cell] : grid.cells()) {
    int classes = 0;
    for (uint16_t n : cell.votes) classes += n > 0;
    if (classes > 1) ++g.conflict_cells;
    if (const auto cls = VoteGrid::winner(cell, min_votes)) won[std::size_t(*cls)].push_back(k);
  }
  for (int c = 0; c < kNumGridClasses; ++c) {
    auto& keys = won[std::size_t(c)];
    std::sort(keys.begin(), keys.end());
    g.class_cells[std::size_t(c)] = keys.size();
    g.voted_cells += keys.size();
  }

  std::vector<MapInstance> out = laneInstances(grid, won[0], params, stats);
  for (int c = 1; c < kNumGridClasses; ++c)
    for (auto& inst : discreteInstances(grid, won[std::size_t(c)], CrowdClass(c)))
      out.push_back(std::move(inst));
  return out;
}

}  // namespace mapfuse::aggregate
