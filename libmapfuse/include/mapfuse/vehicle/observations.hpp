#pragma once
/// @file Per-frame perception output that lsm-build consumes (docs/formats-frames.md
/// "observations.jsonl", or derived from masks / the fallback perception).
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "mapfuse/core/classes.hpp"

namespace mapfuse::vehicle {

/// A ground marking seen in one frame: a centre line (lines) or a polygon ring (planar).
struct GroundObservation {
  CrowdClass cls = CrowdClass::kLaneLine;
  Attributes attributes;
  int64_t track_id = -1;  ///< stable across frames when known, -1 = associate spatially
  int64_t truth_id = -1;  ///< simulator only
  std::vector<Eigen::Vector2d> pixels;  ///< px, pixel centres at integer coordinates
};

/// An aerial element (sign, light, pole) seen in one frame.
struct AerialObservation {
  CrowdClass cls = CrowdClass::kTrafficSign;
  int64_t track_id = -1;  ///< -1 = associate by optical flow
  int64_t truth_id = -1;
  Eigen::Vector4d box = Eigen::Vector4d::Zero();  ///< u_min, v_min, u_max, v_max (px)
  /// Key points (px): sign 4 corners; light [bottom centre, top centre]; pole [base, top].
  /// Empty = use the box (centre for signs, bottom / top centre for lights and poles).
  std::vector<Eigen::Vector2d> points;
};

/// Everything perceived in one camera frame.
struct FrameObservations {
  int index = 0;
  double stamp = 0.0;  ///< s
  std::vector<GroundObservation> ground;
  std::vector<AerialObservation> aerial;
};

}  // namespace mapfuse::vehicle
