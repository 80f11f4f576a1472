#pragma once
/// @file The road hides what lies beyond a crest. A camera 1.4 m above a road that tops a crest
/// 20 m ahead does not see the markings on the far side, however close they are in the image;
/// projecting every marking within range (as the frames writer did) gave a camera that sees
/// through hills, whose pixels no ranging can place (esmini crest-curve: lane pixels of points
/// 30-40 m ahead, behind the crest, among those of the road 12-15 m ahead).
/// The occluder is the road the vehicle is about to drive over: the truth poses ahead of the
/// frame, each with its body origin on the road and its axes along the road (pitch and roll).
/// A point is hidden when the sight line from the camera passes below the road abreast of one of
/// those poses by more than kOcclusionTolerance.
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "mapfuse/core/se3.hpp"

namespace mapfuse::sim {

/// m, how far below the road the sight line must pass to count as hidden (the road between two
/// poses is taken as flat; the body's suspension pitch moves its origin a few mm).
inline constexpr double kOcclusionTolerance = 0.02;

class RoadOcclusion {
 public:
  /// @param T_enu_body the drive's true poses (body origin on the road), in time order
  /// @param step poses examined: every step-th (about a metre apart is enough)
  RoadOcclusion(const std::vector<Pose3>& T_enu_body, std::size_t step);

  /// @brief True when the road along the drive, from pose k on, hides p_enu from the camera at
  /// cam_enu (within max_distance of path ahead).
  bool hidden(std::size_t k, const Eigen::Vector3d& cam_enu, const Eigen::Vector3d& p_enu,
              double max_distance) const;

 private:
  std::vector<Pose3> T_body_enu_;  ///< inverses of the poses
  std::vector<double> distance_;   ///< m, path distance of each pose from the first
  std::size_t step_;
};

}  // namespace mapfuse::sim
