#pragma once
/// @file The road ahead as the drive's own path shows it (issue 33, "lateral ranging that holds").
/// Eq. (1) ranges a pixel on the plane under the camera. Where the road bends vertically (crests,
/// sags, the foot and top of a ramp) the road ahead leaves that plane by δ = κ d²/2: on an 8 %
/// grade wave of 800 m (κ = 6.3e-4 /m) 0.13 m at 20 m, and a ray that meets the road δ above the
/// plane is ranged about δ/h too far (h the camera height: 8 % at 20 m), its lateral offset with
/// it; the frames' errors do not average out.
/// The drive later passes what it sees ahead, and its dead-reckoned heights along the path show
/// the road's vertical profile. Per frame, a least-squares parabola z ≈ a + b d + c d² of the
/// heights (along the drive's mean up axis) against path distance d over [-reach, reach] around
/// the frame gives the road's bend c: the plane under the camera is the road's tangent there, and
/// the road abreast of a point d ahead lies c d² above it. The pixel is ranged again on the plane
/// raised by that much, with d the path distance to the frame abreast of the ranged point (the
/// first frame ahead whose body x axis no longer points at it), until that frame stays the same.
/// The parabola spans 90 m: the dead-reckoned pitch errors (a few 1e-3 rad, corrected by gravity
/// within seconds) average out over it, while road design keeps vertical curves longer than that.
/// Where no frame comes abreast within reach (the drive ends, or turns away) or the point lies
/// farther aside than path_max_offset, the plane under the camera is kept. Cross-slope that
/// changes along the road (superelevation runs) is not modelled: the road ahead keeps the
/// frame's roll.
#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <vector>

#include "mapfuse/core/drive_records.hpp"
#include "mapfuse/core/se3.hpp"
#include "mapfuse/vehicle/ground_ranging.hpp"

namespace mapfuse::vehicle {

/// The drive's path for ranging on the road ahead: per frame the body pose, the ground plane
/// (camera frame), the path distance from the first frame and the road's vertical bend.
class PathSurface {
 public:
  /// @param planes per frame, after tilt and calibration (same size as T_odom_body)
  PathSurface(const std::vector<Pose3>& T_odom_body, const Pose3& T_body_cam,
              const std::vector<GroundPlane>& planes, const RangingSettings& settings);

  /// @brief The first frame after `i` (within the path reach) whose body x axis no longer points at
  /// `p_odom`; nullopt when none within reach, or when the point is more than max_offset aside.
  std::optional<std::size_t> frameAbreast(std::size_t i, const Eigen::Vector3d& p_odom) const;

  /// @brief Height of the road abreast of frame j above the tangent plane of frame i, m
  /// (bend(i) (d_j − d_i)²).
  double riseAhead(std::size_t i, std::size_t j) const;

  /// @brief The road's vertical bend c at frame i (z ≈ a + b d + c d²), 1/m: κ/2.
  double bend(std::size_t i) const { return bend_[i]; }

  /// @brief Eq. (1) on the road ahead: the pixel of frame i ranged on frame i's plane, then on
  /// that plane raised to the road abreast of the point. `on_path` tells whether it was raised.
  std::optional<GroundPoint> range(std::size_t i, const Eigen::Vector2d& pixel,
                                   const Eigen::Matrix3d& K, const RangingSettings& ranging,
                                   bool* on_path = nullptr) const;

  /// Times the pixel is ranged again at most (the frame abreast settles in 1-2 in practice).
  static constexpr int kMaxIterations = 4;

 private:
  const std::vector<Pose3>& T_odom_body_;
  Pose3 T_body_cam_;
  const std::vector<GroundPlane>& planes_;
  double max_offset_;             ///< m (RangingSettings::path_max_offset)
  double reach_;                  ///< m of path ahead searched for the frame abreast
  std::vector<double> distance_;  ///< m, path distance of each frame from the first
  std::vector<double> bend_;      ///< 1/m, per frame
};

}  // namespace mapfuse::vehicle
