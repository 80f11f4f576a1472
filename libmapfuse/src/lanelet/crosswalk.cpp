#include <algorithm>

#include "mapfuse/lanelet/plan.hpp"

namespace mapfuse::lanelet {

std::pair<std::vector<Eigen::Vector3d>, std::vector<Eigen::Vector3d>> crosswalkBounds(
    const std::vector<Eigen::Vector3d>& ring) {
  const std::size_t n = ring.size();
  std::size_t p = 0;
  for (std::size_t k = 1; k < n; ++k)
    if ((ring[(k + 1) % n] - ring[k]).head<2>().norm() >
        (ring[(p + 1) % n] - ring[p]).head<2>().norm())
      p = k;
  std::vector<Eigen::Vector3d> left = {ring[p], ring[(p + 1) % n]}, right;
  for (std::size_t k = 2; k < n; ++k) right.push_back(ring[(p + k) % n]);
  std::reverse(right.begin(), right.end());
  if (right.size() == 1) right.push_back(right.front());  // a triangle: a degenerate bound
  return {left, right};
}

}  // namespace mapfuse::lanelet
