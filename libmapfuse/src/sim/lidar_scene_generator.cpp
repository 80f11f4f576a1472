#include "mapfuse/sim/lidar_scene_generator.hpp"

#include <cmath>
#include <random>

namespace mapfuse::sim {
namespace {

using Rng = std::mt19937_64;

double uniform(Rng& rng, double a, double b) {
  return std::uniform_real_distribution<double>(a, b)(rng);
}
bool chance(Rng& rng, double p) {
  return uniform(rng, 0.0, 1.0) < p;
}

/// Builds primitives while keeping them off the road and sidewalk.
struct SceneBuilder {
  const Road& road;
  std::vector<Primitive>& out;

  /// False when any sample of the footprint lies closer than `min_lateral` to the centreline.
  bool clear(const Primitive& p, double min_lateral) const {
    const double cs = std::cos(p.yaw), sn = std::sin(p.yaw);
    for (int i = -2; i <= 2; ++i)
      for (int j = -2; j <= 2; ++j) {
        const double lx = p.half.x() * i / 2.0, ly = p.half.y() * j / 2.0;
        const double x = p.centre.x() + cs * lx - sn * ly, y = p.centre.y() + sn * lx + cs * ly;
        const RoadCoord c = road.locate(x, y);
        if (c.near && std::abs(c.lateral) < min_lateral) return false;
      }
    return true;
  }

  /// Adds a primitive at road coordinates (s, lateral) rotated with the road.
  Primitive make(Primitive::Kind kind, double s, double lateral, double z, Eigen::Vector3d half,
                 const SurfaceLabel& label) const {
    Primitive p;
    p.kind = kind;
    const Eigen::Vector2d xy = road.pointAt(s, lateral);
    p.centre = {xy.x(), xy.y(), z};
    p.half = half;
    p.yaw = road.headingAt(s);
    p.label = label;
    return p;
  }

  bool add(const Primitive& p, double min_lateral) {
    if (!clear(p, min_lateral)) return false;
    out.push_back(p);
    return true;
  }
};

const SurfaceLabel kBuilding{LidarClass::kBuilding, 50, 0, 0.35f};
const SurfaceLabel kFence{LidarClass::kFence, 51, 0, 0.30f};
const SurfaceLabel kPole{LidarClass::kPole, 80, 0, 0.40f};
const SurfaceLabel kSign{LidarClass::kPole, 81, 0, 0.85f};         // traffic sign counts as pole
const SurfaceLabel kTrunk{LidarClass::kVegetation, 70, 0, 0.25f};  // trunks count as vegetation
const SurfaceLabel kFoliage{LidarClass::kVegetation, 70, 0, 0.20f};

void addTree(SceneBuilder& b, Rng& rng, double s, double lateral, double ground,
             double min_lateral) {
  const double trunk_h = uniform(rng, 1.8, 3.0), trunk_r = uniform(rng, 0.12, 0.25);
  Primitive trunk = b.make(Primitive::Kind::kCylinder, s, lateral, ground + 0.5 * trunk_h,
                           {trunk_r, trunk_r, 0.5 * trunk_h}, kTrunk);
  if (!b.add(trunk, min_lateral)) return;
  // Crown: a few jittered ellipsoids so the foliage is irregular.
  const double r = uniform(rng, 1.5, 2.6);
  const int blobs = 2 + static_cast<int>(uniform(rng, 0.0, 2.99));
  for (int k = 0; k < blobs; ++k) {
    Primitive crown = trunk;
    crown.kind = Primitive::Kind::kEllipsoid;
    // Drawn z, y, x: the order of the release (gcc) build (sim/draw_order.hpp).
    const double dz = r * uniform(rng, 0.5, 0.9), dy = uniform(rng, -0.6, 0.6),
                 dx = uniform(rng, -0.6, 0.6);
    crown.centre += Eigen::Vector3d(dx, dy, 0.5 * trunk_h + dz);
    crown.half = {r * uniform(rng, 0.7, 1.1), r * uniform(rng, 0.7, 1.1),
                  r * uniform(rng, 0.6, 0.9)};
    crown.yaw = uniform(rng, 0.0, M_PI);
    crown.label = kFoliage;
    b.out.push_back(crown);
  }
}

void addFrontage(SceneBuilder& b, Rng& rng, const StreetParams& P, double side) {
  const RoadProfile& rp = P.profile;
  const double line = rp.road_half_width + rp.sidewalk_width;  // property line
  const double h = rp.curb_height, L = b.road.length();
  double s = 0.0;
  while (s < L) {
    const double u = uniform(rng, 0.0, 1.0);
    if (u < P.building_share) {
      double len = uniform(rng, 10.0, 25.0);
      const double depth = uniform(rng, 8.0, 14.0);
      const double height = uniform(rng, P.building_height_min, P.building_height_max);
      const double setback = uniform(rng, 0.0, 1.5);
      for (int attempt = 0; attempt < 3; ++attempt, len *= 0.5) {
        const Primitive p =
            b.make(Primitive::Kind::kBox, s + 0.5 * len, side * (line + setback + 0.5 * depth),
                   h + 0.5 * height, {0.5 * len, 0.5 * depth, 0.5 * height}, kBuilding);
        if (b.add(p, line - 0.05)) break;
      }
      s += len + uniform(rng, 0.0, 2.5);
    } else if (u < P.building_share + P.fence_share) {
      const double len = uniform(rng, 8.0, 20.0), height = uniform(rng, 1.2, 2.0);
      for (double a = 0.0; a < len; a += 2.0)  // short pieces follow curves
        b.add(b.make(Primitive::Kind::kBox, s + a + 1.0, side * (line + 0.1), h + 0.5 * height,
                     {1.0, 0.04, 0.5 * height}, kFence),
              line - 0.05);
      for (double a = uniform(rng, 1.0, 5.0); a < len; a += uniform(rng, 5.0, 9.0))
        addTree(b, rng, s + a, side * (line + uniform(rng, 3.0, 6.0)), h, line + 0.5);
      s += len + uniform(rng, 0.0, 1.5);
    } else {
      const double len = uniform(rng, 6.0, 16.0);
      for (double a = 0.0; a < len; a += uniform(rng, 0.9, 1.4)) {
        const double hz = uniform(rng, 0.6, 1.0);
        Primitive p = b.make(Primitive::Kind::kEllipsoid, s + a, side * (line + 0.9), h + 0.7 * hz,
                             {uniform(rng, 0.9, 1.4), uniform(rng, 0.5, 0.8), hz}, kFoliage);
        p.yaw += uniform(rng, -0.3, 0.3);
        b.add(p, line - 0.3);  // hedges may brush the property line, never the sidewalk
      }
      s += len + uniform(rng, 0.0, 1.5);
    }
  }
  // Sidewalk furniture: poles (some carrying a sign) and trees.
  for (double a = uniform(rng, 0.0, P.pole_spacing); a < L;
       a += P.pole_spacing * uniform(rng, 0.6, 1.4)) {
    const double height = uniform(rng, 4.5, 8.0), r = uniform(rng, 0.07, 0.14);
    const double lat = side * (rp.road_half_width + 0.45);
    b.add(b.make(Primitive::Kind::kCylinder, a, lat, h + 0.5 * height, {r, r, 0.5 * height}, kPole),
          rp.road_half_width + 0.2);
    if (chance(rng, 0.5))
      b.out.push_back(
          b.make(Primitive::Kind::kBox, a, lat, h + height - 0.6, {0.05, 0.35, 0.35}, kSign));
  }
  for (double a = uniform(rng, 0.0, P.tree_spacing); a < L;
       a += P.tree_spacing * uniform(rng, 0.6, 1.4))
    addTree(b, rng, a, side * (line - 0.9), h, rp.road_half_width + 0.5);
}

}  // namespace

LidarScene generateStreet(const StreetParams& P, uint64_t seed) {
  Rng rng(seed);
  const std::vector<double> straights{uniform(rng, P.straight_min, P.straight_max),
                                      uniform(rng, P.straight_min, P.straight_max),
                                      uniform(rng, P.straight_min, P.straight_max)};
  const std::vector<double> radii{uniform(rng, P.turn_radius_min, P.turn_radius_max),
                                  uniform(rng, P.turn_radius_min, P.turn_radius_max)};
  const std::vector<double> angles{
      (chance(rng, 0.5) ? 1.0 : -1.0) * M_PI / 2,
      (chance(rng, 0.5) ? 1.0 : -1.0) * uniform(rng, 0.5, 1.0) * M_PI / 2};
  const RoadProfile& rp = P.profile;
  // 1 m samples: chord error below 1 cm for radii above 12.5 m. Lateral coordinates are only
  // needed a little beyond the property line (placement checks use at most line + 0.5 m).
  Road road(makeCentreline(straights, radii, angles, 1.0), rp,
            rp.road_half_width + rp.sidewalk_width + 2.0);
  std::vector<Primitive> statics;
  SceneBuilder b{road, statics};
  addFrontage(b, rng, P, +1.0);
  addFrontage(b, rng, P, -1.0);

  // Parked cars on the right-hand curb, in stretches of about 30 m.
  uint16_t instance = 1;
  const double L = road.length();
  const double park_lat = -(rp.road_half_width - 1.1);
  for (double stretch = 0.0; stretch < L; stretch += 30.0) {
    if (!chance(rng, P.parked_share)) continue;
    for (double s = stretch + uniform(rng, 0.0, 4.0); s < std::min(L, stretch + 30.0);) {
      // Drawn height, width, length: the order of the release (gcc) build (draw_order.hpp).
      const double height = uniform(rng, 1.4, 1.7), width = uniform(rng, 1.7, 1.9),
                   length = uniform(rng, 4.0, 4.8);
      const Eigen::Vector3d size(length, width, height);
      const SurfaceLabel label{LidarClass::kVehicle, 10, instance++, 0.45f};
      const Eigen::Vector2d xy = road.pointAt(s + 0.5 * size.x(), park_lat);
      for (auto& p :
           LidarScene::carPrimitives(xy, road.headingAt(s + 0.5 * size.x()), size, 0.0, label))
        statics.push_back(p);
      s += size.x() + uniform(rng, 1.0, 8.0);
    }
  }

  // Moving cars: oncoming ones in the left lane, and ones ahead of the ego in its lane that are
  // at least as fast as the ego (so they never run into the sensor).
  std::vector<MovingVehicle> movers;
  for (int k = 0; k < P.moving_vehicles; ++k) {
    MovingVehicle m;
    m.size = {uniform(rng, 4.0, 4.8), uniform(rng, 1.7, 1.9), uniform(rng, 1.4, 1.7)};
    m.instance = static_cast<uint16_t>(1000 + k);
    if (k % 2 == 0) {
      m.lateral = 0.5 * rp.lane_width;
      m.s0 = P.ego_start + uniform(rng, 30.0, 0.6 * L);
      m.speed = -uniform(rng, 5.0, 12.0);
    } else {
      m.lateral = -0.5 * rp.lane_width;
      m.s0 = P.ego_start + uniform(rng, 10.0, 40.0) * (1 + k / 2);
      m.speed = P.ego_speed + uniform(rng, 0.0, 3.0);
    }
    movers.push_back(m);
  }
  return LidarScene(std::move(road), std::move(statics), std::move(movers));
}

}  // namespace mapfuse::sim
