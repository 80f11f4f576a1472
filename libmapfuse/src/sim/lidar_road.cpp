#include "mapfuse/sim/lidar_road.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mapfuse/core/error.hpp"

namespace mapfuse::sim {

Road::Road(std::vector<Eigen::Vector2d> centreline, RoadProfile profile, double query_radius)
    : pts_(std::move(centreline)), profile_(profile), radius_(query_radius) {
  if (pts_.size() < 2) throw InputError("road centreline needs at least 2 points");
  s_.assign(pts_.size(), 0.0);
  for (std::size_t i = 1; i < pts_.size(); ++i) {
    const double d = (pts_[i] - pts_[i - 1]).norm();
    if (!(d > 0.0)) throw InputError("road centreline has repeated points");
    s_[i] = s_[i - 1] + d;
  }
  Eigen::Vector2d lo = pts_[0], hi = pts_[0];
  for (const auto& p : pts_) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  min_ = lo - Eigen::Vector2d::Constant(radius_ + cell_);
  nx_ = static_cast<int>(std::ceil((hi.x() - min_.x() + radius_ + cell_) / cell_)) + 1;
  ny_ = static_cast<int>(std::ceil((hi.y() - min_.y() + radius_ + cell_) / cell_)) + 1;
  // Each cell lists the segments whose bounding box, grown by the query radius, touches it.
  std::vector<std::vector<uint32_t>> cells(static_cast<std::size_t>(nx_) * ny_);
  for (std::size_t i = 0; i + 1 < pts_.size(); ++i) {
    const Eigen::Vector2d a = pts_[i].cwiseMin(pts_[i + 1]).array() - radius_;
    const Eigen::Vector2d b = pts_[i].cwiseMax(pts_[i + 1]).array() + radius_;
    const int x0 = static_cast<int>((a.x() - min_.x()) / cell_);
    const int x1 = static_cast<int>((b.x() - min_.x()) / cell_);
    const int y0 = static_cast<int>((a.y() - min_.y()) / cell_);
    const int y1 = static_cast<int>((b.y() - min_.y()) / cell_);
    for (int y = std::max(0, y0); y <= std::min(ny_ - 1, y1); ++y)
      for (int x = std::max(0, x0); x <= std::min(nx_ - 1, x1); ++x)
        cells[static_cast<std::size_t>(y) * nx_ + x].push_back(static_cast<uint32_t>(i));
  }
  cell_start_.assign(cells.size() + 1, 0);
  for (std::size_t c = 0; c < cells.size(); ++c) {
    cell_start_[c + 1] = cell_start_[c] + static_cast<uint32_t>(cells[c].size());
    cell_items_.insert(cell_items_.end(), cells[c].begin(), cells[c].end());
  }
}

RoadCoord Road::locate(double x, double y) const {
  RoadCoord out;
  out.lateral = std::numeric_limits<double>::infinity();
  const int cx = static_cast<int>(std::floor((x - min_.x()) / cell_));
  const int cy = static_cast<int>(std::floor((y - min_.y()) / cell_));
  if (cx < 0 || cy < 0 || cx >= nx_ || cy >= ny_) return out;
  const std::size_t c = static_cast<std::size_t>(cy) * nx_ + cx;
  double best = radius_ * radius_;
  const Eigen::Vector2d p(x, y);
  for (uint32_t k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
    const uint32_t i = cell_items_[k];
    const Eigen::Vector2d a = pts_[i], ab = pts_[i + 1] - pts_[i];
    const double len2 = ab.squaredNorm();
    const double u = std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
    const Eigen::Vector2d q = a + u * ab;
    const double d2 = (p - q).squaredNorm();
    if (d2 < best) {
      best = d2;
      const double cross = ab.x() * (p.y() - a.y()) - ab.y() * (p.x() - a.x());
      out.lateral = cross >= 0.0 ? std::sqrt(d2) : -std::sqrt(d2);
      out.s = s_[i] + u * std::sqrt(len2);
      out.near = true;
    }
  }
  return out;
}

Eigen::Vector2d Road::pointAt(double s, double lateral) const {
  s = std::clamp(s, 0.0, s_.back());
  const auto it = std::upper_bound(s_.begin(), s_.end(), s);
  const std::size_t i = std::min<std::size_t>(
      static_cast<std::size_t>(std::max<std::ptrdiff_t>(it - s_.begin() - 1, 0)), pts_.size() - 2);
  const Eigen::Vector2d ab = pts_[i + 1] - pts_[i];
  const double len = ab.norm();
  const Eigen::Vector2d t = ab / len, n(-t.y(), t.x());
  return pts_[i] + (s - s_[i]) * t + lateral * n;
}

double Road::headingAt(double s) const {
  const double h = 1.0;
  const Eigen::Vector2d d = pointAt(s + h, 0.0) - pointAt(s - h, 0.0);
  return std::atan2(d.y(), d.x());
}

GroundKind Road::groundAt(const RoadCoord& c) const {
  const double a = std::abs(c.lateral);
  if (!c.near || a >= profile_.road_half_width + profile_.sidewalk_width)
    return GroundKind::kTerrain;
  if (a >= profile_.road_half_width) return GroundKind::kSidewalk;
  const double w = 0.5 * profile_.marking_width;
  if (a < w && std::fmod(c.s, profile_.dash_length + profile_.dash_gap) < profile_.dash_length)
    return GroundKind::kLaneMarking;
  const double edge = profile_.road_half_width - profile_.edge_line_offset;
  if (std::abs(a - edge) < w) return GroundKind::kLaneMarking;
  return GroundKind::kRoad;
}

double Road::groundHeight(const RoadCoord& c) const {
  return (c.near && std::abs(c.lateral) < profile_.road_half_width) ? 0.0 : profile_.curb_height;
}

std::vector<Eigen::Vector2d> makeCentreline(const std::vector<double>& straights,
                                            const std::vector<double>& turn_radii,
                                            const std::vector<double>& turn_angles,
                                            double spacing) {
  if (turn_radii.size() != turn_angles.size() || straights.size() != turn_radii.size() + 1)
    throw InputError("makeCentreline: need one more straight than turns");
  if (!(spacing > 0.0)) throw InputError("makeCentreline: spacing must be positive");
  std::vector<Eigen::Vector2d> pts{Eigen::Vector2d::Zero()};
  Eigen::Vector2d p = Eigen::Vector2d::Zero();
  double heading = 0.0;
  for (std::size_t k = 0; k < straights.size(); ++k) {
    const int n = std::max(1, static_cast<int>(std::round(straights[k] / spacing)));
    const Eigen::Vector2d dir(std::cos(heading), std::sin(heading));
    for (int i = 1; i <= n; ++i) pts.push_back(p + dir * (straights[k] * i / n));
    p = pts.back();
    if (k == turn_radii.size()) break;
    // Circular arc of signed angle (left positive) about the centre to the side of the turn.
    const double r = turn_radii[k], ang = turn_angles[k];
    const double side = ang >= 0.0 ? 1.0 : -1.0;
    const Eigen::Vector2d centre = p + side * r * Eigen::Vector2d(-dir.y(), dir.x());
    const double a0 = std::atan2(p.y() - centre.y(), p.x() - centre.x());
    const int m = std::max(2, static_cast<int>(std::ceil(std::abs(ang) * r / spacing)));
    for (int i = 1; i <= m; ++i) {
      const double a = a0 + ang * i / m;
      pts.push_back(centre + r * Eigen::Vector2d(std::cos(a), std::sin(a)));
    }
    p = pts.back();
    heading += ang;
  }
  return pts;
}

}  // namespace mapfuse::sim
