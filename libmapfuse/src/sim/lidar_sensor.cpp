#include "mapfuse/sim/lidar_sensor.hpp"

#include <algorithm>
#include <cmath>

namespace mapfuse::sim {
namespace {
uint64_t splitmix(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}
double deg(double d) {
  return d * M_PI / 180.0;
}
}  // namespace

uint64_t hashKey(uint64_t a, uint64_t b, uint64_t c, uint64_t d) {
  return splitmix(splitmix(splitmix(splitmix(a) ^ b) ^ c) ^ d);
}

double hashUniform(uint64_t key) {
  return static_cast<double>(splitmix(key) >> 11) * (1.0 / 9007199254740992.0);
}

std::vector<double> beamElevations(const LidarSensorParams& p) {
  const int upper = p.beams / 2, lower = p.beams - upper;
  std::vector<double> out;
  for (int i = 0; i < upper; ++i)
    out.push_back(deg(p.upper_top + (p.upper_bottom - p.upper_top) * i / std::max(1, upper - 1)));
  for (int i = 0; i < lower; ++i)
    out.push_back(deg(p.lower_top + (p.lower_bottom - p.lower_top) * i / std::max(1, lower - 1)));
  return out;
}

LidarScan scanLidar(const LidarScene& scene, const Pose3& T_world_velo, double time,
                    const LidarSensorParams& p, uint64_t seed) {
  const std::vector<double> elev = beamElevations(p);
  const std::vector<Primitive> dynamic = scene.dynamicAt(time);
  const Eigen::Matrix3d R = T_world_velo.linear();
  const Eigen::Vector3d o = T_world_velo.translation();
  const int nb = static_cast<int>(elev.size());
  std::vector<LidarScan> per_beam(static_cast<std::size_t>(nb));
#pragma omp parallel for schedule(dynamic, 1)
  for (int b = 0; b < nb; ++b) {
    LidarScan& out = per_beam[static_cast<std::size_t>(b)];
    out.points.reserve(static_cast<std::size_t>(p.azimuth_steps));
    out.labels.reserve(static_cast<std::size_t>(p.azimuth_steps));
    const double ce = std::cos(elev[b]), se = std::sin(elev[b]);
    for (int a = 0; a < p.azimuth_steps; ++a) {
      const uint64_t key = hashKey(seed, static_cast<uint64_t>(b), static_cast<uint64_t>(a));
      if (hashUniform(key) < p.dropout) continue;
      // Counter-clockwise from the x axis (forward), as the Velodyne frame.
      const double az = 2.0 * M_PI * a / p.azimuth_steps;
      const Eigen::Vector3d d_velo(ce * std::cos(az), ce * std::sin(az), se);
      const RayHit hit = scene.cast(o, R * d_velo, p.max_range, dynamic);
      if (!hit.hit() || hit.t < p.min_range) continue;
      // Box-Muller from two more counter-based uniforms.
      const double u1 = std::max(hashUniform(key + 1), 1e-300), u2 = hashUniform(key + 2);
      const double g = std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
      const double g2 = std::sqrt(-2.0 * std::log(u1)) * std::sin(2.0 * M_PI * u2);
      const double range = hit.t + p.range_noise * g;
      const double refl = std::clamp(hit.label.reflectance + p.reflectance_noise * g2, 0.0, 1.0);
      const Eigen::Vector3d q = d_velo * range;
      out.points.emplace_back(static_cast<float>(q.x()), static_cast<float>(q.y()),
                              static_cast<float>(q.z()), static_cast<float>(refl));
      out.labels.push_back(hit.label.word());
    }
  }
  LidarScan scan;
  for (auto& s : per_beam) {
    scan.points.insert(scan.points.end(), s.points.begin(), s.points.end());
    scan.labels.insert(scan.labels.end(), s.labels.begin(), s.labels.end());
  }
  return scan;
}

}  // namespace mapfuse::sim
