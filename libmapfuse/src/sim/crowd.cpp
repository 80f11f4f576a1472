#include "mapfuse/sim/crowd.hpp"

#include <cstdio>

namespace mapfuse::sim {
namespace {

/// Seed indices of the world and the routes (traversal i uses index i).
constexpr uint64_t kWorldSeedIndex = 1000001;
constexpr uint64_t kRoutesSeedIndex = 1000002;

std::string driveId(int vehicle, int traversal) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "veh%02d_trav%03d", vehicle, traversal);
  return buf;
}

}  // namespace

void CrowdStats::add(const CrowdStats& s) {
  drives.add(s.drives);
  observations.elements += s.observations.elements;
  observations.false_positives += s.observations.false_positives;
  observations.missed += s.observations.missed;
  observations.partial_stop_lines += s.observations.partial_stop_lines;
  frames.frames += s.frames.frames;
  frames.ground_observations += s.frames.ground_observations;
  frames.aerial_observations += s.frames.aerial_observations;
}

std::vector<Polyline> crowdRoutes(const World& world, const CrowdSettings& s) {
  return planRoutes(world, s.routes, s.route_length, deriveSeed(s.seed, kRoutesSeedIndex),
                    s.route_outward);
}

Crowd::Crowd(const World& world, const geo::GeoOrigin& origin, const CrowdSettings& s)
    : world_(world),
      settings_(s),
      routes_(crowdRoutes(world, s)),
      index_(world, s.obs.point_spacing),
      camera_(s.camera),
      enu_(origin) {}

Traversal Crowd::traversal(int i, CrowdStats* stats) const {
  const CrowdSettings& P = settings_;
  Traversal t;
  t.seed = deriveSeed(P.seed, static_cast<uint64_t>(i));
  DriveParams dp = P.drive;  // the injected biases of the trust tests (docs/simulate.md)
  if (i == P.inject_pitch_traversal) dp.imu_pitch_mount += P.inject_pitch;
  if (i == P.inject_wheel_traversal) dp.wheel_scale_offset += P.inject_wheel_scale;
  t.drive = simulateDrive(routes_[i % routes_.size()], dp, enu_, deriveSeed(t.seed, 1),
                          world_.surface_height);
  t.drive.vehicle_id = driveId(i % P.vehicles, 0).substr(0, 5);
  t.drive.drive_id = driveId(i % P.vehicles, i);
  t.observed = observeLsm(world_, index_, t.drive, camera_, P.obs, P.drive, deriveSeed(t.seed, 2));
  if (stats) {
    stats->drives.add(t.drive, t.observed.keyframe_samples, P.drive);
    stats->observations = t.observed.stats;
  }
  return t;
}

FramesStats Crowd::writeFrames(const Traversal& t, const std::filesystem::path& dir) const {
  return writeFramesDrive(dir, world_, index_, t.drive, camera_, settings_.drive, settings_.frames,
                          deriveSeed(t.seed, 3));
}

World proceduralWorld(const CrowdSettings& s, const geo::GeoOrigin& origin) {
  return buildProceduralWorld(s.world, origin, deriveSeed(s.seed, kWorldSeedIndex));
}

std::vector<std::size_t> cameraSamples(const Drive& d, const DriveParams& DP) {
  const std::size_t every = cameraStride(DP);
  std::vector<std::size_t> samples;
  for (std::size_t k = 0; k < d.stamps.size(); k += every) samples.push_back(k);
  return samples;
}

}  // namespace mapfuse::sim
