#include "mapfuse/sim/lidar_scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mapfuse::sim {
namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kParallel = 1e-12;     // |direction component| below which a slab is parallel
constexpr double kSphereMargin = 1e-9;  // relative and m, of a primitive's bounding sphere

/// Ray (o, d) rotated into the frame of a primitive rotated by `yaw` about z at `c`.
inline void toLocal(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& c,
                    double yaw, Eigen::Vector3d& ol, Eigen::Vector3d& dl) {
  const double cs = std::cos(yaw), sn = std::sin(yaw);
  const Eigen::Vector3d r = o - c;
  ol = {cs * r.x() + sn * r.y(), -sn * r.x() + cs * r.y(), r.z()};
  dl = {cs * d.x() + sn * d.y(), -sn * d.x() + cs * d.y(), d.z()};
}

/// Clips [lo, hi] by the slab |o + t d| <= h along one axis; false when empty.
inline bool slab(double o, double d, double h, double& lo, double& hi) {
  if (std::abs(d) < kParallel) return std::abs(o) <= h;
  double t0 = (-h - o) / d, t1 = (h - o) / d;
  if (t0 > t1) std::swap(t0, t1);
  lo = std::max(lo, t0);
  hi = std::min(hi, t1);
  return lo <= hi;
}
}  // namespace

double Primitive::intersect(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double tmin,
                            double tmax) const {
  // Most rays a cell's primitives are tried against pass them by: the sphere around the box or
  // ellipsoid (radius |half|, with a margin for rounding) rules those out before the ray is
  // rotated into the primitive's frame (whose sin and cos were a third of simulate-lidar's time).
  if (kind != Kind::kCylinder) {
    const Eigen::Vector3d r = o - centre;
    const double b = r.dot(d), radius = half.norm() * (1.0 + kSphereMargin) + kSphereMargin;
    const double c = r.squaredNorm() - radius * radius;
    if (b * b - c < 0.0 || (c > 0.0 && b > 0.0)) return -1.0;
  }
  double lo = -kInf, hi = kInf;
  switch (kind) {
    case Kind::kBox: {
      Eigen::Vector3d ol, dl;
      toLocal(o, d, centre, yaw, ol, dl);
      if (!slab(ol.x(), dl.x(), half.x(), lo, hi) || !slab(ol.y(), dl.y(), half.y(), lo, hi) ||
          !slab(ol.z(), dl.z(), half.z(), lo, hi))
        return -1.0;
      break;
    }
    case Kind::kCylinder: {
      const double ox = o.x() - centre.x(), oy = o.y() - centre.y();
      const double a = d.x() * d.x() + d.y() * d.y();
      const double c = ox * ox + oy * oy - half.x() * half.x();
      if (a < kParallel) {
        if (c > 0.0) return -1.0;
      } else {
        const double b = ox * d.x() + oy * d.y();
        const double disc = b * b - a * c;
        if (disc < 0.0) return -1.0;
        const double sq = std::sqrt(disc);
        lo = (-b - sq) / a;
        hi = (-b + sq) / a;
      }
      if (!slab(o.z() - centre.z(), d.z(), half.z(), lo, hi)) return -1.0;
      break;
    }
    case Kind::kEllipsoid: {
      Eigen::Vector3d ol, dl;
      toLocal(o, d, centre, yaw, ol, dl);
      ol = ol.cwiseQuotient(half);
      dl = dl.cwiseQuotient(half);
      const double a = dl.squaredNorm(), b = ol.dot(dl), c = ol.squaredNorm() - 1.0;
      const double disc = b * b - a * c;
      if (disc < 0.0) return -1.0;
      const double sq = std::sqrt(disc);
      lo = (-b - sq) / a;
      hi = (-b + sq) / a;
      break;
    }
  }
  return (lo > tmin && lo <= tmax) ? lo : -1.0;
}

Eigen::Vector4d Primitive::footprint() const {
  double rx = half.x(), ry = half.y();
  if (kind != Kind::kCylinder) {
    const double cs = std::abs(std::cos(yaw)), sn = std::abs(std::sin(yaw));
    rx = cs * half.x() + sn * half.y();
    ry = sn * half.x() + cs * half.y();
  }
  return {centre.x() - rx, centre.y() - ry, centre.x() + rx, centre.y() + ry};
}

LidarScene::LidarScene(Road road, std::vector<Primitive> statics, std::vector<MovingVehicle> movers,
                       double cell_size)
    : road_(std::move(road)),
      statics_(std::move(statics)),
      movers_(std::move(movers)),
      cell_(cell_size) {
  Eigen::Vector2d lo(kInf, kInf), hi(-kInf, -kInf);
  for (const auto& p : statics_) {
    const Eigen::Vector4d f = p.footprint();
    lo = lo.cwiseMin(f.head<2>());
    hi = hi.cwiseMax(f.tail<2>());
    zmax_ = std::max(zmax_, p.centre.z() + p.half.z());
  }
  if (statics_.empty()) lo = hi = Eigen::Vector2d::Zero();
  min_ = lo;
  nx_ = static_cast<int>((hi.x() - lo.x()) / cell_) + 1;
  ny_ = static_cast<int>((hi.y() - lo.y()) / cell_) + 1;
  std::vector<std::vector<uint32_t>> cells(static_cast<std::size_t>(nx_) * ny_);
  for (std::size_t i = 0; i < statics_.size(); ++i) {
    const Eigen::Vector4d f = statics_[i].footprint();
    const int x0 = static_cast<int>((f[0] - min_.x()) / cell_);
    const int y0 = static_cast<int>((f[1] - min_.y()) / cell_);
    const int x1 = std::min(nx_ - 1, static_cast<int>((f[2] - min_.x()) / cell_));
    const int y1 = std::min(ny_ - 1, static_cast<int>((f[3] - min_.y()) / cell_));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x)
        cells[static_cast<std::size_t>(y) * nx_ + x].push_back(static_cast<uint32_t>(i));
  }
  cell_start_.assign(cells.size() + 1, 0);
  for (std::size_t c = 0; c < cells.size(); ++c) {
    cell_start_[c + 1] = cell_start_[c] + static_cast<uint32_t>(cells[c].size());
    cell_items_.insert(cell_items_.end(), cells[c].begin(), cells[c].end());
  }
}

SurfaceLabel LidarScene::groundLabel(GroundKind kind) {
  switch (kind) {
    case GroundKind::kRoad: return {LidarClass::kRoad, 40, 0, 0.22f};
    case GroundKind::kLaneMarking: return {LidarClass::kRoad, 60, 0, 0.75f};
    case GroundKind::kSidewalk: return {LidarClass::kSidewalk, 48, 0, 0.30f};
    case GroundKind::kTerrain: break;
  }
  return {LidarClass::kVegetation, 72, 0, 0.18f};  // terrain counts as vegetation
}

std::vector<Primitive> LidarScene::carPrimitives(const Eigen::Vector2d& xy, double heading,
                                                 const Eigen::Vector3d& size, double ground_z,
                                                 const SurfaceLabel& label) {
  // Body: lower 60 % of the height raised by the wheels' clearance; cabin: upper part, shorter.
  const double clearance = 0.25, body_h = 0.55 * size.z() - clearance;
  Primitive body;
  body.kind = Primitive::Kind::kBox;
  body.centre = {xy.x(), xy.y(), ground_z + clearance + 0.5 * body_h};
  body.half = {0.5 * size.x(), 0.5 * size.y(), 0.5 * body_h};
  body.yaw = heading;
  body.label = label;
  Primitive cabin = body;
  const double cabin_h = size.z() - clearance - body_h;
  const Eigen::Vector2d back(-std::cos(heading), -std::sin(heading));
  cabin.centre = {xy.x() + 0.1 * size.x() * back.x(), xy.y() + 0.1 * size.x() * back.y(),
                  ground_z + clearance + body_h + 0.5 * cabin_h};
  cabin.half = {0.28 * size.x(), 0.45 * size.y(), 0.5 * cabin_h};
  Primitive wheels = body;  // the wheel band below the body, a bit narrower
  wheels.centre.z() = ground_z + 0.5 * clearance;
  wheels.half = {0.42 * size.x(), 0.47 * size.y(), 0.5 * clearance};
  return {body, cabin, wheels};
}

std::vector<Primitive> LidarScene::dynamicAt(double time) const {
  std::vector<Primitive> out;
  for (const auto& m : movers_) {
    const double s = m.s0 + m.speed * time;
    if (s < 0.0 || s > road_.length()) continue;
    const Eigen::Vector2d xy = road_.pointAt(s, m.lateral);
    const double heading = road_.headingAt(s) + (m.speed < 0.0 ? M_PI : 0.0);
    const SurfaceLabel label{LidarClass::kVehicle, kSemanticKittiMovingCar, m.instance, 0.45f};
    for (auto& p : carPrimitives(xy, heading, m.size, 0.0, label)) out.push_back(p);
  }
  return out;
}

RayHit LidarScene::castGround(const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                              double tmax) const {
  RayHit hit;
  const double h = road_.profile().curb_height;
  if (d.z() > -kParallel || o.z() < h) return hit;
  const double th = (h - o.z()) / d.z(), t0 = (0.0 - o.z()) / d.z();
  if (th > tmax) return hit;
  const Eigen::Vector3d ph = o + th * d;
  const RoadCoord ch = road_.locate(ph.x(), ph.y());
  const double half = road_.profile().road_half_width;
  if (!ch.near || std::abs(ch.lateral) >= half) {  // lands on sidewalk or terrain
    hit.t = th;
    hit.label = groundLabel(road_.groundAt(ch));
    return hit;
  }
  if (t0 > tmax) return hit;
  const Eigen::Vector3d p0 = o + t0 * d;
  const RoadCoord c0 = road_.locate(p0.x(), p0.y());
  if (c0.near && std::abs(c0.lateral) < half) {
    hit.t = t0;
    hit.label = groundLabel(road_.groundAt(c0));
    return hit;
  }
  // Between the two heights the ray leaves the road: it meets the curb face (sidewalk class).
  double a = th, b = t0;
  for (int i = 0; i < 20; ++i) {
    const double m = 0.5 * (a + b);
    const Eigen::Vector3d pm = o + m * d;
    const RoadCoord cm = road_.locate(pm.x(), pm.y());
    if (cm.near && std::abs(cm.lateral) < half)
      a = m;
    else
      b = m;
  }
  hit.t = b;
  hit.label = groundLabel(GroundKind::kSidewalk);
  return hit;
}

RayHit LidarScene::cast(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double tmax,
                        const std::vector<Primitive>& dynamic) const {
  RayHit best = castGround(o, d, tmax);
  double limit = best.hit() ? best.t : tmax;
  constexpr double kTmin = 1e-6;
  for (const auto& p : dynamic) {
    const double t = p.intersect(o, d, kTmin, limit);
    if (t >= 0.0) {
      limit = t;
      best.t = t;
      best.label = p.label;
    }
  }
  // 2D DDA through the grid of static primitives (Amanatides & Woo), stopping once the
  // nearest hit lies before the current cell's exit or the ray has climbed above everything.
  const double fx = (o.x() - min_.x()) / cell_, fy = (o.y() - min_.y()) / cell_;
  double t = 0.0;
  // Advance to the grid if the origin is outside it.
  {
    double lo = 0.0, hi = limit;
    const Eigen::Vector2d extent(nx_ * cell_, ny_ * cell_);
    if (!slab(o.x() - min_.x() - 0.5 * extent.x(), d.x(), 0.5 * extent.x(), lo, hi) ||
        !slab(o.y() - min_.y() - 0.5 * extent.y(), d.y(), 0.5 * extent.y(), lo, hi))
      return best;
    t = lo;
  }
  int cx = std::clamp(static_cast<int>(std::floor(fx + t * d.x() / cell_)), 0, nx_ - 1);
  int cy = std::clamp(static_cast<int>(std::floor(fy + t * d.y() / cell_)), 0, ny_ - 1);
  const int sx = d.x() > 0 ? 1 : -1, sy = d.y() > 0 ? 1 : -1;
  const double ddx = std::abs(d.x()) > kParallel ? cell_ / std::abs(d.x()) : kInf;
  const double ddy = std::abs(d.y()) > kParallel ? cell_ / std::abs(d.y()) : kInf;
  double nxt_x = std::abs(d.x()) > kParallel
                     ? ((cx + (sx > 0 ? 1 : 0)) * cell_ + min_.x() - o.x()) / d.x()
                     : kInf;
  double nxt_y = std::abs(d.y()) > kParallel
                     ? ((cy + (sy > 0 ? 1 : 0)) * cell_ + min_.y() - o.y()) / d.y()
                     : kInf;
  while (true) {
    const std::size_t c = static_cast<std::size_t>(cy) * nx_ + cx;
    for (uint32_t k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
      const Primitive& p = statics_[cell_items_[k]];
      const double th = p.intersect(o, d, kTmin, limit);
      if (th >= 0.0) {
        limit = th;
        best.t = th;
        best.label = p.label;
      }
    }
    const double exit = std::min(nxt_x, nxt_y);
    if (exit >= limit) break;
    if (d.z() > 0.0 && o.z() + exit * d.z() > zmax_) break;
    if (nxt_x < nxt_y) {
      cx += sx;
      nxt_x += ddx;
      if (cx < 0 || cx >= nx_) break;
    } else {
      cy += sy;
      nxt_y += ddy;
      if (cy < 0 || cy >= ny_) break;
    }
  }
  return best;
}

}  // namespace mapfuse::sim
