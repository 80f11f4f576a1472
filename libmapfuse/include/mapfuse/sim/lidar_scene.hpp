#pragma once
/// @file The synthetic LiDAR street as analytic primitives (boxes, vertical cylinders,
/// ellipsoids) over the road ground, with a coarse 2D acceleration grid, and the nearest-hit
/// ray query the LiDAR and the camera share (docs/lidar-ground-truth.md).
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "mapfuse/core/classes.hpp"
#include "mapfuse/sim/lidar_road.hpp"

namespace mapfuse::sim {

/// SemanticKITTI id of a moving car (lidarClassFromSemanticKitti maps it to vehicle).
constexpr uint16_t kSemanticKittiMovingCar = 252;

/// What a surface is: class, SemanticKITTI id, instance and reflectance.
struct SurfaceLabel {
  LidarClass cls = LidarClass::kUnlabeled;
  uint16_t kitti_id = 0;    ///< SemanticKITTI semantic id (low 16 bits of a .label)
  uint16_t instance = 0;    ///< instance id (high 16 bits of a .label), 0 = stuff
  float reflectance = 0.f;  ///< KITTI-style remission in [0, 1]
  /// @brief The SemanticKITTI .label word: semantic id | instance << 16.
  uint32_t word() const { return static_cast<uint32_t>(kitti_id) | (uint32_t(instance) << 16); }
};

/// One analytic solid. Boxes and ellipsoids are rotated about z by `yaw`; cylinders are upright.
struct Primitive {
  enum class Kind : uint8_t { kBox, kCylinder, kEllipsoid } kind = Kind::kBox;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< m, world
  Eigen::Vector3d half =
      Eigen::Vector3d::Ones();  ///< m, half extents / radii (cylinder: r, r, h/2)
  double yaw = 0.0;             ///< rad
  SurfaceLabel label;

  /// @brief Entry distance of the ray o + t d (|d| = 1) in (tmin, tmax), or a negative value.
  double intersect(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double tmin,
                   double tmax) const;
  /// @brief 2D bounding box (min x, min y, max x, max y) in m.
  Eigen::Vector4d footprint() const;
};

/// A vehicle driving along the road: arc length s(t) = s0 + speed * t (direction +-1).
struct MovingVehicle {
  double s0 = 0.0;                      ///< m, arc length at t = 0
  double speed = 0.0;                   ///< m/s, signed along the centreline
  double lateral = 0.0;                 ///< m, left positive
  Eigen::Vector3d size{4.2, 1.8, 1.5};  ///< m, length, width, height
  uint16_t instance = 0;
};

/// Result of a ray query.
struct RayHit {
  double t = -1.0;  ///< m along the unit ray, negative = no hit
  SurfaceLabel label;
  bool hit() const { return t >= 0.0; }
};

/// Static world (road ground + primitives in a grid) plus moving vehicles.
class LidarScene {
 public:
  LidarScene(Road road, std::vector<Primitive> statics, std::vector<MovingVehicle> movers,
             double cell_size = 2.0);

  /// @brief Primitives of the moving vehicles at time `time` (s).
  std::vector<Primitive> dynamicAt(double time) const;

  /// @brief Nearest surface along o + t d, t in (0, tmax]; d must be unit length.
  /// @param dynamic moving-vehicle primitives of this instant (from dynamicAt()).
  RayHit cast(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double tmax,
              const std::vector<Primitive>& dynamic) const;

  /// @brief Nearest ground hit only (road, markings, sidewalk with curb, terrain).
  RayHit castGround(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double tmax) const;

  const Road& road() const { return road_; }
  const std::vector<Primitive>& statics() const { return statics_; }
  const std::vector<MovingVehicle>& movers() const { return movers_; }

  /// @brief Labels of the ground kinds (public so tests and the camera agree).
  static SurfaceLabel groundLabel(GroundKind kind);
  /// @brief Primitives of a car (body + cabin) at a 2D position and heading.
  static std::vector<Primitive> carPrimitives(const Eigen::Vector2d& xy, double heading,
                                              const Eigen::Vector3d& size, double ground_z,
                                              const SurfaceLabel& label);

 private:
  Road road_;
  std::vector<Primitive> statics_;
  std::vector<MovingVehicle> movers_;
  double cell_;
  Eigen::Vector2d min_;
  int nx_ = 0, ny_ = 0;
  double zmax_ = 0.0;
  std::vector<uint32_t> cell_start_, cell_items_;
};

}  // namespace mapfuse::sim
