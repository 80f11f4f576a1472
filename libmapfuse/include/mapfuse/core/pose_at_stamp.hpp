#pragma once
/// @file The pose of a time-stamped trajectory at any instant inside it (dead reckoning at
/// camera stamps, odometry at GPS stamps, the true trajectory at keyframe stamps).
#include <cstddef>
#include <optional>

#include "mapfuse/core/se3.hpp"

namespace mapfuse {

/// @brief Pose at time `t` on a trajectory of `n` samples sorted by stamp: sample i has
/// `stamp_at(i)` and `pose_at(i)`. A sample within `same` seconds of t is returned as it is;
/// between two samples the pose is interpolated geodesically (interpolate()); before the first
/// or after the last sample there is none (nullopt): callers decide whether to clamp or skip.
template <class StampAt, class PoseAt>
std::optional<Pose3> poseAtStamp(std::size_t n, double t, StampAt stamp_at, PoseAt pose_at,
                                 double same = 0.0) {
  std::size_t lo = 0, hi = n;  // first sample with stamp >= t
  while (lo < hi) {
    const std::size_t mid = lo + (hi - lo) / 2;
    if (stamp_at(mid) < t)
      lo = mid + 1;
    else
      hi = mid;
  }
  if (lo < n && stamp_at(lo) - t <= same) return Pose3(pose_at(lo));
  if (lo > 0 && t - stamp_at(lo - 1) <= same) return Pose3(pose_at(lo - 1));
  if (lo == 0 || lo == n) return std::nullopt;
  const double t0 = stamp_at(lo - 1), span = stamp_at(lo) - t0;
  return interpolate(pose_at(lo - 1), pose_at(lo), span > 0.0 ? (t - t0) / span : 0.0);
}

}  // namespace mapfuse
