#pragma once
/// @file Hand-built ground truth and noisy ENU LSMs for the aggregate tests (no simulator):
/// a straight road along +x with parallel lane lines, optionally a fork (a line leaving the
/// right edge line) or a merge (a line joining the left edge line), poles, signs, arrows, a
/// crosswalk and a stop line. Drives alternate direction; every observation carries a per-drive
/// offset, a per-element offset and per-point noise (all Gaussian, seeded).
#include <cstdint>
#include <random>
#include <vector>

#include "mapfuse/aggregate/observations.hpp"
#include "mapfuse/core/lsm.hpp"
#include "mapfuse/core/vector_map.hpp"

namespace mapfuse::test {

struct SynthOptions {
  int drives = 10;
  double length = 200.0;        ///< m of road
  bool fork = false;            ///< branch leaves line y = 0 at x = length / 2, heading -6 deg
  bool merge = false;           ///< a line joins line y = 7 at x = length / 2 from y = 13
  bool discrete = true;         ///< poles, signs, arrows, crosswalk, stop line
  double crossing_deg = 0.0;    ///< > 0: a 30 m line crossing all lines at (crossing_x, 3.5)
  double crossing_x = 100.0;    ///< m, where the crossing line meets the middle line
  double crosswalk_deg = 90.0;  ///< angle of the crosswalk's 7 m sides to the road (90: rectangle)
  double drive_sigma = 0.05;    ///< m, per-drive offset (alignment residual)
  double element_sigma = 0.03;  ///< m, per-element offset
  double point_sigma = 0.03;    ///< m, per-point noise
  double view = 25.0;           ///< m, length of road seen from one keyframe
  double keyframe_step = 10.0;  ///< m
  int false_positives = 0;      ///< random false elements per drive (each class but lanes)
  double dash_length = 0.0;     ///< m, > 0: dashed lines are observed dash by dash
  double dash_gap = 6.0;        ///< m, between dashes (with dash_length > 0)
  uint64_t seed = 1;
  geo::GeoOrigin origin{49.0110, 8.4228, 112.8};
};

struct SynthWorld {
  VectorMap truth;
  std::vector<Lsm> lsms;
};

SynthWorld makeSynthWorld(const SynthOptions& options);

/// @brief The world's LSMs as aggregate's observations (sources named by drive id).
aggregate::ObservationSet observe(const SynthWorld& w);
/// @brief The map's instances of class `c`.
std::vector<const MapInstance*> ofClass(const VectorMap& m, CrowdClass c);
/// @brief Distance in the xy plane from p to the nearest true instance of class `c`, m.
double distanceToTruth(const Eigen::Vector3d& p, const VectorMap& truth, CrowdClass c);

}  // namespace mapfuse::test
