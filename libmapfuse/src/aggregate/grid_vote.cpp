#include "grid_vote.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "mapfuse/aggregate/geometry2d.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/io/bounds.hpp"

namespace mapfuse::aggregate {
namespace {

using Vec3 = Eigen::Vector3d;

// Cell budget of voteGrid: a real observation paints a few hundred cells (a 30 m lane line at
// 0.1 m: ~600; a crosswalk: ~4000); absurd geometry within the readers' bounds is refused
// before it exhausts memory.
constexpr double kCellsPerObservation = 65536;
constexpr double kMinCellBudget = 4e6;

// Whether (x, y) lies inside the ring (crossing number; the ring is not closed).
bool insideRing(const std::vector<Vec3>& ring, double x, double y) {
  bool inside = false;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    const Vec3 &a = ring[i], &b = ring[j];
    if ((a.y() > y) != (b.y() > y) && x < (b.x() - a.x()) * (y - a.y()) / (b.y() - a.y()) + a.x())
      inside = !inside;
  }
  return inside;
}

}  // namespace

void VoteGrid::paint(const Observation& o, double line_width, std::vector<PaintedCell>& out) const {
  if (!isGridClass(o.cls) || o.points.empty()) return;
  auto index = [&](double v) { return int64_t(std::floor(v / cell_)); };
  auto add = [&](int64_t ix, int64_t iy, double z) {
    out.push_back({key(ix, iy), float(z), o.cls, o.attributes});
  };
  if (geometryKind(o.cls) == GeometryKind::kLine) {
    const double half = std::max(0.5 * line_width, 0.5 * cell_);
    const std::size_t n = o.points.size();
    for (std::size_t s = 0; s + 1 < std::max<std::size_t>(n, 2); ++s) {
      const Vec3& a = o.points[s];
      const Vec3& b = o.points[std::min(s + 1, n - 1)];
      for (int64_t ix = index(std::min(a.x(), b.x()) - half);
           ix <= index(std::max(a.x(), b.x()) + half); ++ix)
        for (int64_t iy = index(std::min(a.y(), b.y()) - half);
             iy <= index(std::max(a.y(), b.y()) + half); ++iy) {
          const Vec3 c((double(ix) + 0.5) * cell_, (double(iy) + 0.5) * cell_, 0.0);
          Vec3 foot;
          if (distanceToSegment2d(c, a, b, &foot) <= half) add(ix, iy, foot.z());
        }
    }
    return;
  }
  // ground polygon: the cells whose centre is inside
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300, z = 0;
  for (const auto& p : o.points) {
    x0 = std::min(x0, p.x()), x1 = std::max(x1, p.x());
    y0 = std::min(y0, p.y()), y1 = std::max(y1, p.y());
    z += p.z();
  }
  z /= double(o.points.size());
  for (int64_t ix = index(x0); ix <= index(x1); ++ix)
    for (int64_t iy = index(y0); iy <= index(y1); ++iy)
      if (insideRing(o.points, (double(ix) + 0.5) * cell_, (double(iy) + 0.5) * cell_))
        add(ix, iy, z);
}

void VoteGrid::vote(std::vector<PaintedCell>& painted) {
  // one vote per cell and class: strokes overlap at their joints, and observations of one drive
  // overlap each other
  auto before = [](const PaintedCell& a, const PaintedCell& b) {
    return a.key != b.key ? a.key < b.key : a.cls < b.cls;
  };
  std::stable_sort(painted.begin(), painted.end(), before);
  auto add = [](uint16_t& count) {
    if (count < UINT16_MAX) ++count;
  };
  for (std::size_t i = 0; i < painted.size(); ++i) {
    const PaintedCell& p = painted[i];
    if (i > 0 && painted[i - 1].key == p.key && painted[i - 1].cls == p.cls) continue;
    GridCell& c = cells_[p.key];
    add(c.votes[std::size_t(p.cls)]);
    if (p.cls == CrowdClass::kLaneLine) {
      add(c.style[std::size_t(p.attributes.style)]);
      add(c.color[std::size_t(p.attributes.color)]);
    }
    c.z_sum += p.z;
    ++votes_;
  }
}

double VoteGrid::cellsBound(const Observation& o, double line_width) const {
  if (!isGridClass(o.cls) || o.points.empty()) return 0;
  if (geometryKind(o.cls) == GeometryKind::kLine) {
    const double span = 2 * std::max(0.5 * line_width, 0.5 * cell_) / cell_ + 2;
    double cells = 0;
    for (std::size_t s = 0; s + 1 < std::max<std::size_t>(o.points.size(), 2); ++s) {
      const Vec3& a = o.points[s];
      const Vec3& b = o.points[std::min(s + 1, o.points.size() - 1)];
      cells += (std::abs(b.x() - a.x()) / cell_ + span) * (std::abs(b.y() - a.y()) / cell_ + span);
    }
    return cells;
  }
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const auto& p : o.points) {
    x0 = std::min(x0, p.x()), x1 = std::max(x1, p.x());
    y0 = std::min(y0, p.y()), y1 = std::max(y1, p.y());
  }
  return ((x1 - x0) / cell_ + 2) * ((y1 - y0) / cell_ + 2);
}

std::optional<CrowdClass> VoteGrid::winner(const GridCell& cell, int min_votes) {
  int best = 0;
  for (int c = 1; c < kNumGridClasses; ++c)
    if (cell.votes[std::size_t(c)] > cell.votes[std::size_t(best)]) best = c;
  if (int(cell.votes[std::size_t(best)]) < min_votes) return std::nullopt;
  return CrowdClass(best);
}

Eigen::Vector3d VoteGrid::centre(int64_t k) const {
  const GridCell& c = cells_.at(k);
  int total = 0;
  for (uint16_t v : c.votes) total += v;
  return {(double(ix(k)) + 0.5) * cell_, (double(iy(k)) + 0.5) * cell_,
          total > 0 ? double(c.z_sum) / total : 0.0};
}

VoteGrid voteGrid(const std::vector<Observation>& items, const std::vector<std::size_t>& indices,
                  const GridVoteParams& p) {
  VoteGrid grid(p.cell_size);
  double total = 0, largest = 0;
  std::size_t worst = indices.empty() ? 0 : indices.front();
  for (std::size_t i : indices) {
    const double n = grid.cellsBound(items[i], p.line_width);
    total += n;
    if (n > largest) largest = n, worst = i;
  }
  const double budget = std::max(kMinCellBudget, kCellsPerObservation * double(indices.size()));
  if (total > budget)
    throw InputError("ground observations would paint " + io::bounds::numberText(total) +
                     " grid cells of " + io::bounds::numberText(p.cell_size) + " m (limit " +
                     io::bounds::numberText(budget) + "): element " +
                     std::to_string(items[worst].element_id) + " of input LSM #" +
                     std::to_string(items[worst].drive + 1) + " (command-line order) paints " +
                     io::bounds::numberText(largest));
  // drive by drive (stable: the observations of a drive in input order)
  std::vector<std::size_t> order = indices;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return items[a].drive < items[b].drive; });
  std::vector<PaintedCell> painted;
  for (std::size_t k = 0; k < order.size(); ++k) {
    grid.paint(items[order[k]], p.line_width, painted);
    if (k + 1 == order.size() || items[order[k + 1]].drive != items[order[k]].drive) {
      grid.vote(painted);
      painted.clear();
    }
  }
  return grid;
}

}  // namespace mapfuse::aggregate
