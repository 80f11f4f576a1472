#include "mapfuse/tiling/piece_links.hpp"

#include <algorithm>
#include <map>

#include "mapfuse/fusion/voxel_hash.hpp"

namespace mapfuse::tiling {

std::vector<std::pair<int, int>> agreeingPieces(const std::vector<Lsm>& aligned, double distance,
                                                int min_points) {
  // Element points in ENU with their piece, per class.
  std::vector<std::vector<Eigen::Vector3d>> points(kNumCrowdClasses);
  std::vector<std::vector<int>> owner(kNumCrowdClasses);
  for (int l = 0; l < int(aligned.size()); ++l)
    for (const Element& e : aligned[l].elements) {
      const Pose3& T = aligned[l].keyframes[aligned[l].keyframeIndex(e.anchor)].T_frame_body;
      for (const auto& p : e.points_body) {
        points[int(e.cls)].push_back(T * p);
        owner[int(e.cls)].push_back(l);
      }
    }
  // count[(a, b)]: points of a with a point of b within `distance`.
  std::map<std::pair<int, int>, int> count;
  std::vector<int> seen;
  for (int c = 0; c < kNumCrowdClasses; ++c) {
    if (points[c].empty()) continue;
    const fusion::VoxelIndex index(points[c], distance);
    for (std::size_t i = 0; i < points[c].size(); ++i) {
      seen.clear();
      index.forEachWithin(points[c][i], distance * distance, [&](int j, double) {
        const int other = owner[c][j];
        if (other != owner[c][i] && std::find(seen.begin(), seen.end(), other) == seen.end())
          seen.push_back(other);
      });
      for (int other : seen) ++count[{owner[c][i], other}];
    }
  }
  // Linked when either piece has enough points on the other.
  std::map<std::pair<int, int>, int> best;
  for (const auto& [pair, n] : count) {
    int& b = best[std::minmax(pair.first, pair.second)];
    b = std::max(b, n);
  }
  std::vector<std::pair<int, int>> links;
  for (const auto& [pair, n] : best)
    if (n >= min_points) links.push_back(pair);
  return links;
}

}  // namespace mapfuse::tiling
