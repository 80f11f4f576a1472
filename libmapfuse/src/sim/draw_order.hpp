// Vectors of random draws in a fixed order, whatever the compiler.
//
// `Eigen::Vector3d(N01(rng), N01(rng), N01(rng))` leaves the order of the three draws to the
// compiler (function arguments are unsequenced): gcc draws z, y, x, clang x, y, z, so one seed
// gave other drives, frames and LiDAR errors under clang. These helpers draw in gcc's order, so
// that every output of the release (gcc) build stays byte-identical and clang's equals it.
#pragma once

#include <Eigen/Core>

namespace mapfuse::sim {

/// Three draws of `dist`, z first, then y, then x (the order the release build always used).
template <class Dist, class Rng>
Eigen::Vector3d drawVector3(Dist& dist, Rng& rng) {
  const double z = dist(rng);
  const double y = dist(rng);
  const double x = dist(rng);
  return {x, y, z};
}

/// Two draws of `dist`, y first, then x.
template <class Dist, class Rng>
Eigen::Vector2d drawVector2(Dist& dist, Rng& rng) {
  const double y = dist(rng);
  const double x = dist(rng);
  return {x, y};
}

}  // namespace mapfuse::sim
