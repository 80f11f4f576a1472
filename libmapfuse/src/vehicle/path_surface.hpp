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
/// the road abreast of a point d ahead lies c d² above it. The parabola spans 90 m: the
/// dead-reckoned pitch errors (a few 1e-3 rad, corrected by gravity within seconds) average out
/// over it. Where the heights leave that parabola by more than a few centimetres (a short steep
/// crest or sag: esmini crest-curve climbs 6 m in 70 m and comes down in 70 m) the road abreast
/// is the profile itself, z(d_j) − z(d_i) − z'(d_i)(d_j − d_i), smoothed over ±2 m, with the
/// slope z' of a parabola over ±11 m (sharpVerticalCurves; body_tilt takes the same frames).
/// The pixel's ray is marched along the path: it meets the road abreast of the first frame j
/// ahead where its intersection with the tangent plane raised to j's road no longer lies ahead
/// of j (the rise interpolated between j − 1 and j). (Re-ranging on the road abreast of the
/// last estimate, the first version, did not converge on crests: a rise error δ moves a point
/// ~δ d / h.) Two rays are not ranged at all: one the march carries past the reach while the
/// path goes on (it passes over a crest), and one whose point moves by more than a tenth of its
/// range when the road is taken 5 cm lower (it runs close along the road: ill-conditioned). The
/// covariance is that of eq. (1) on the road's own plane there, through the same point.
/// Across the path the road abreast of frame j lies along frame j's own ground plane: a point y
/// aside is n_i · across_j · y above the path there. On a curve up a grade this is the twist of
/// the road ahead seen from frame i (a point towards the curve's centre is less far ahead than
/// the path abreast, where frame i's tangent plane is lower); where the crossfall changes ahead
/// (superelevation runs) it is that change, as frame j's plane shows it.
/// Where the drive ends before a ray meets the road, the road goes on along the last frame's own
/// ground plane, carried into frame i by the dead-reckoned poses: a drive that ends at an
/// intersection sees its far side 20-30 m beyond the last frame, and on the 8 % world the plane
/// under the camera put those stop lines and crosswalks 3-8 m short. Where the point
/// lies farther aside than path_max_offset of a frame abreast that the path reached by turning
/// (a road straight on where the drive turns off), the plane under the camera is kept; along a
/// path that runs straight a point may lie as far aside as the band reaches (a crossing road's
/// stop lines and crosswalks 15-25 m aside: on the 8 % world the plane under the camera ranged
/// them 4-8 m short, a second element beside the right one).
#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <vector>

#include "mapfuse/core/drive_records.hpp"
#include "mapfuse/core/se3.hpp"
#include "mapfuse/vehicle/ground_ranging.hpp"

namespace mapfuse::vehicle {

/// @brief Per frame: the road bends vertically more than one parabola over the path's reach
/// follows (its dead-reckoned heights leave the parabola by more than a few centimetres): a
/// short steep crest or sag, where the profile itself is ranged on and the body tilt is taken
/// as a local quadratic (body_tilt.hpp).
std::vector<bool> sharpVerticalCurves(const std::vector<Pose3>& T_odom_body,
                                      const RangingSettings& settings);

/// The drive's path for ranging on the road ahead: per frame the body pose, the ground plane
/// (camera frame), the path distance from the first frame and the road's vertical bend.
class PathSurface {
 public:
  /// @param planes per frame, after tilt and calibration (same size as T_odom_body)
  PathSurface(const std::vector<Pose3>& T_odom_body, const Pose3& T_body_cam,
              const std::vector<GroundPlane>& planes, const RangingSettings& settings);

  /// @brief Height of the road abreast of frame j above the tangent plane of frame i, m
  /// (bend(i) (d_j − d_i)²).
  double riseAhead(std::size_t i, std::size_t j) const;

  /// @brief Slope of the road abreast of frame j against the tangent plane of frame i.
  double slopeAhead(std::size_t i, std::size_t j) const;

  /// @brief The road's vertical bend c at frame i (z ≈ a + b d + c d²), 1/m: κ/2.
  double bend(std::size_t i) const { return bend_[i]; }

  /// @brief Eq. (1) on the road ahead: the pixel of frame i ranged on frame i's plane, then on
  /// that plane raised to the road abreast of the point. `on_path` tells whether it was raised.
  std::optional<GroundPoint> range(std::size_t i, const Eigen::Vector2d& pixel,
                                   const Eigen::Matrix3d& K, const RangingSettings& ranging,
                                   bool* on_path = nullptr) const;

 private:
  /// Where a ray of frame i meets the road ahead: its rise and slope against frame i's tangent;
  /// met = false when the path runs on beyond the reach and the ray never meets the road.
  struct Crossing {
    bool met = false;
    double rise = 0.0, slope = 0.0;
  };
  /// @brief The march along the path for `pixel` of frame i, the road taken `lowered` m lower.
  std::optional<Crossing> cross(std::size_t i, const Eigen::Vector2d& pixel,
                                const Eigen::Matrix3d& K_inv, double lowered) const;
  /// @brief The ray still ahead of the drive's last frame: met on the road that continues along
  /// that frame's ground plane (nullopt: it does not, the plane under the camera is kept).
  std::optional<Crossing> beyondEnd(std::size_t i, const Eigen::Vector2d& pixel,
                                    const Eigen::Matrix3d& K_inv, double lowered) const;
  /// Where the ray of frame i meets frame i's tangent plane raised by `rise` and twisted to
  /// frame j's plane across the path: the point in body j (x ahead) and the rise used there.
  struct Meeting {
    Eigen::Vector3d q;
    double rise = 0.0;
  };
  /// @brief The path's heading turned by more than kStraightTurn from frame i to frame j.
  bool turned(std::size_t i, std::size_t j) const;
  std::optional<Meeting> meet(std::size_t i, std::size_t j, const Eigen::Vector2d& pixel,
                              const Eigen::Matrix3d& K_inv, double rise) const;

  const std::vector<Pose3>& T_odom_body_;
  std::vector<Pose3> T_body_odom_;  ///< inverses, per frame
  std::vector<Pose3> T_odom_cam_;   ///< camera poses, per frame
  const std::vector<GroundPlane>& planes_;
  double max_offset_;             ///< m (RangingSettings::path_max_offset)
  double reach_;                  ///< m of path ahead searched for the frame abreast
  std::vector<double> distance_;  ///< m, path distance of each frame from the first
  std::vector<double> bend_;      ///< 1/m, per frame
  std::vector<bool> profile_;     ///< per frame: no parabola follows the road, the profile does
  std::vector<double> height_;    ///< m, dead-reckoned heights smoothed along the path
  std::vector<double> slope_;     ///< the road's slope per frame (a short parabola's tangent)
  std::vector<Eigen::Vector3d> up_;      ///< per frame, its ground plane's normal in odom
  std::vector<Eigen::Vector3d> across_;  ///< per frame, the road's left across the path in odom
};

}  // namespace mapfuse::vehicle
