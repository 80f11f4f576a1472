#pragma once
/// @file Posts the simulator places under signs and lights when a map has no poles of its own:
/// signs and lights mounted together (a sign plate above another, a light with its sign, 0.2-0.6
/// m apart on the Karlsruhe Lanelet2 map) share one post, as they do on a street. Two truth poles
/// that close would ask a map for two poles no camera can tell apart (evaluate matches one
/// map pole to one truth pole).
#include <Eigen/Core>
#include <vector>

namespace mapfuse::sim {

/// m: a sign or light this close (horizontally) to an existing post is mounted on it
constexpr double kSharedPostRadius = 1.0;

class SignPosts {
 public:
  /// True when no post stands within kSharedPostRadius of `base`; then `base` is one.
  bool claim(const Eigen::Vector3d& base) {
    for (const auto& p : posts_)
      if ((p - base.head<2>()).norm() < kSharedPostRadius) return false;
    posts_.push_back(base.head<2>());
    return true;
  }

 private:
  std::vector<Eigen::Vector2d> posts_;
};

}  // namespace mapfuse::sim
