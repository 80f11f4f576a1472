#pragma once
/// @file HDL-64E-like LiDAR model (docs/lidar-ground-truth.md): 64 beams in two blocks
/// (upper +2.0..-8.33 deg, lower -8.83..-24.33 deg), a full turn of azimuth steps per scan,
/// Gaussian range noise and random dropouts; every returned point carries its true label.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "mapfuse/core/param.hpp"
#include "mapfuse/core/se3.hpp"
#include "mapfuse/sim/lidar_scene.hpp"

namespace mapfuse::sim {

struct LidarSensorParams {
  int beams = 64;                   ///< lasers, half in each block
  double upper_top = 2.0;           ///< deg, elevation of the highest laser
  double upper_bottom = -8.33;      ///< deg, lowest laser of the upper block
  double lower_top = -8.83;         ///< deg, highest laser of the lower block
  double lower_bottom = -24.33;     ///< deg, lowest laser
  int azimuth_steps = 2150;         ///< rays per laser per turn
  double min_range = 2.5;           ///< m, closer returns are dropped (ego vehicle)
  double max_range = 120.0;         ///< m
  double range_noise = 0.02;        ///< m, standard deviation along the ray
  double dropout = 0.03;            ///< probability a return is lost
  double reflectance_noise = 0.05;  ///< standard deviation of the remission

  template <class V>
  void visit(V& v) {
    using namespace param;
    // a scan holds up to beams * azimuth_steps points
    v("lidar_beams", beams, "",
      "lasers: half in the upper block, the rest in the lower (HDL-64E: 64)", in(2, 1024));
    v("azimuth_steps", azimuth_steps, "", "LiDAR rays per laser per turn", in(8, 36000));
    v("lidar_upper_top", upper_top, "deg", "elevation of the highest laser", in(-90, 90));
    v("lidar_upper_bottom", upper_bottom, "deg", "lowest laser of the upper block", in(-90, 90));
    v("lidar_lower_top", lower_top, "deg", "highest laser of the lower block", in(-90, 90));
    v("lidar_lower_bottom", lower_bottom, "deg", "lowest laser", in(-90, 90));
    v.relation("lidar_upper_bottom", upper_bottom, upper_bottom < upper_top, "< lidar_upper_top");
    v.relation("lidar_lower_top", lower_top, lower_top <= upper_bottom, "<= lidar_upper_bottom");
    v.relation("lidar_lower_bottom", lower_bottom, lower_bottom < lower_top, "< lidar_lower_top");
    v("lidar_min_range", min_range, "m", "closer returns are dropped", in(0, 10000));
    v("lidar_max_range", max_range, "m", "farthest return", gt(0) & le(10000));
    v.relation("lidar_min_range", min_range, min_range < max_range, "< lidar_max_range");
    v("range_noise", range_noise, "m", "standard deviation of the range", in(0, 100));
    v("dropout", dropout, "", "probability that a return is lost", in(0, 1) & lt(1));
    v("reflectance_noise", reflectance_noise, "", "standard deviation of the remission (0-1)",
      in(0, 1));
  }
};

/// One scan in the Velodyne frame, with the true label of every point.
struct LidarScan {
  std::vector<Eigen::Vector4f> points;  ///< x, y, z (m, velo frame), reflectance [0, 1]
  std::vector<uint32_t> labels;         ///< SemanticKITTI words (semantic | instance << 16)
};

/// @brief Elevation angles (rad) of the lasers, top first.
std::vector<double> beamElevations(const LidarSensorParams& params);

/// @brief Casts one scan from pose T_world_velo at time `time` (s).
/// @param seed noise seed; the result depends only on (scene, pose, time, params, seed),
/// not on the number of threads.
LidarScan scanLidar(const LidarScene& scene, const Pose3& T_world_velo, double time,
                    const LidarSensorParams& params, uint64_t seed);

/// @brief Counter-based random number in [0, 1) from a key (splitmix64), thread-independent.
double hashUniform(uint64_t key);
/// @brief Mixes several integers into one hash key.
uint64_t hashKey(uint64_t a, uint64_t b, uint64_t c = 0, uint64_t d = 0);

}  // namespace mapfuse::sim
