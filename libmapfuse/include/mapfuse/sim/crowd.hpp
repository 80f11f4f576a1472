#pragma once
/// @file The crowd of drives of `simulate` (docs/simulate.md): routes planned over one world,
/// traversals of them by a fleet of vehicles, each with its own seeds (so the order they are
/// simulated in does not matter), what each vehicle uploads (its LSM) and the statistics of
/// their errors against what the configured sigmas predict.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "mapfuse/core/param.hpp"
#include "mapfuse/geo/origin.hpp"
#include "mapfuse/sim/drive.hpp"
#include "mapfuse/sim/drive_statistics.hpp"
#include "mapfuse/sim/frames_writer.hpp"
#include "mapfuse/sim/lsm_observer.hpp"
#include "mapfuse/sim/procedural_world.hpp"
#include "mapfuse/sim/sim_camera.hpp"
#include "mapfuse/sim/world.hpp"

namespace mapfuse::sim {

/// Parameters of the crowd; each declared once, in the visit() of the struct that owns it.
struct CrowdSettings {
  uint64_t seed = 42;               ///< every random draw derives from it
  int traversals = 20;              ///< drives
  int vehicles = 4;                 ///< traversal i uses vehicle i % vehicles
  int routes = 4;                   ///< distinct routes; traversal i drives route i % routes
  double route_length = 1500.0;     ///< m
  bool route_outward = false;       ///< routes never turn back towards their start
  int inject_pitch_traversal = -1;  ///< this traversal's IMU is pitched by inject_pitch
  double inject_pitch = 0.0087;     ///< rad (0.5 deg)
  int inject_wheel_traversal = -1;  ///< this traversal's wheel scale is off by inject_wheel_scale
  double inject_wheel_scale = 0.02;
  ProceduralParams world;  ///< the procedural world (when no map is given)
  DriveParams drive;
  CameraParams camera;
  ObservationParams obs;
  FramesParams frames;

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("seed", seed, "", "random seed (same seed, same bytes)", in(0, 4294967295.0));
    v("traversals", traversals, "", "number of traversals (drives)", in(1, 100000));
    v("vehicles", vehicles, "", "number of vehicles; traversal i uses vehicle i % vehicles",
      in(1, 100000));
    v("routes", routes, "", "distinct routes; traversal i drives route i % routes", in(1, 10000));
    v("route_length", route_length, "m", "target length of a route", in(50, 1e6));
    v("route_outward", route_outward, "",
      "routes take the successor leading farthest from their start (they never loop back)");
    v("inject_pitch_traversal", inject_pitch_traversal, "",
      "traversal whose IMU is mounted pitched by inject_pitch (-1: none)", in(-1, 1000000));
    v("inject_pitch", inject_pitch, "rad", "injected IMU mount pitch", in(-0.5, 0.5));
    v("inject_wheel_traversal", inject_wheel_traversal, "",
      "traversal whose wheel scale is off by inject_wheel_scale (-1: none)", in(-1, 1000000));
    v("inject_wheel_scale", inject_wheel_scale, "", "injected wheel scale error", in(-0.5, 0.5));
    world.visit(v);
    drive.visit(v);
    // a drive holds route_length / speed * imu_rate samples of ~0.4 kB
    v.relation("route_length", route_length,
               route_length / drive.speed_min * drive.imu_rate <= kMaxDriveSamples,
               "/ speed_min * imu_rate <= 2e6 IMU samples per drive");
    camera.visit(v);
    obs.visit(v);
    frames.visit(v);
  }
  static constexpr double kMaxDriveSamples = 2e6;
};

/// One simulated traversal.
struct Traversal {
  Drive drive;             ///< ids veh<vv>_trav<iii>; true and sensed motion at the IMU rate
  ObservedDrive observed;  ///< the LSM its vehicle uploads, keyframes, observation counts
  uint64_t seed = 0;       ///< this traversal's own seed
};

/// What traversals add up to (simulate.summary.json).
struct CrowdStats {
  DriveStatistics drives;
  ObservationStats observations;
  FramesStats frames;  ///< --level frames only

  /// @brief Adds another's sums and counts (add in traversal order: sums are reproducible).
  void add(const CrowdStats& other);
};

/// @brief The crowd's routes over `world` (deterministic in settings.seed; the lanes only, not the
/// truth, so a changed world keeps them).
std::vector<Polyline> crowdRoutes(const World& world, const CrowdSettings& settings);

/// The fleet on one world: routes planned once, any traversal on demand.
class Crowd {
 public:
  /// @brief Plans the routes and indexes the world's observable pieces. The world must outlive
  /// the Crowd.
  Crowd(const World& world, const geo::GeoOrigin& origin, const CrowdSettings& settings);

  /// @brief Simulates traversal i: its drive, what its vehicle observes, and the statistics of
  /// both in stats (thread-safe, deterministic in i).
  Traversal traversal(int i, CrowdStats* stats = nullptr) const;

  /// @brief Writes the raw frames folder of a traversal (simulate --level frames) to `dir`.
  FramesStats writeFrames(const Traversal& traversal, const std::filesystem::path& dir) const;

 private:
  const World& world_;
  CrowdSettings settings_;
  std::vector<Polyline> routes_;
  PieceIndex index_;
  SimCamera camera_;
  geo::EnuConverter enu_;
};

/// @brief The procedural world of the crowd's seed (ProceduralParams, centred on `origin`).
World proceduralWorld(const CrowdSettings& settings, const geo::GeoOrigin& origin);

/// @brief Indices of the IMU-rate samples at which the camera fires (as the frames writer
/// picks them).
std::vector<std::size_t> cameraSamples(const Drive& drive, const DriveParams& params);

}  // namespace mapfuse::sim
