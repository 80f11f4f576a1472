#pragma once
/// @file Map-relative registration of new drives (docs/update.md "Registration to the map"):
/// the map's elements are fixed targets, each stretch of a new drive is registered to them by
/// semantic GICP (fusion::alignGicp, eq. (7) of Song et al. 2023, with a Huber loss so that
/// changed elements do not pull it), and the offsets per stretch, smoothed along the drive, move
/// the drive's keyframes (and with them its elements).
#include <Eigen/Core>
#include <vector>

#include "mapfuse/core/lsm.hpp"
#include "mapfuse/core/param.hpp"
#include "mapfuse/core/vector_map.hpp"

namespace mapfuse::update {

struct RegistrationSettings {
  bool enabled = true;                              ///< register the drives to the map
  double stretch_length = 150.0;                    ///< m of keyframe path per registered stretch
  std::vector<double> distances = {2.0, 1.0, 0.5};  ///< m, max correspondence per GICP level
  double huber = 3.0;                               ///< sigma, Huber delta on whitened residuals
  int min_inliers = 30;                             ///< a stretch with fewer is not registered
  double stretch_sigma = 2.0;     ///< m, a stretch's coarse shift about its neighbour's
  double smooth_rate = 0.02;      ///< m of offset change per m of path between keyframes
  double smooth_yaw_rate = 5e-4;  ///< rad of yaw change per m of path between keyframes
  int refine_iterations = 5;      ///< per-keyframe refinement iterations per distance level

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("registration", enabled, "",
      "map (register each stretch of a new drive to the map's elements) | none",
      Names<bool>{{{"none", false}, {"map", true}}});
    v("register_stretch_length", stretch_length, "m", "keyframe path per registered stretch",
      in(10, 100000));
    v("register_distances", distances, "m",
      "GICP max correspondence distance per level, coarse to fine", listOf(1, 8, gt(0) & le(20)));
    v("register_huber", huber, "sigma", "Huber delta on whitened GICP residuals (0: none)",
      in(0, 1e6));
    v("register_min_inliers", min_inliers, "", "a stretch with fewer correspondences is skipped",
      in(6, 1000000));
    v("register_stretch_sigma", stretch_sigma, "m",
      "prior sigma of a stretch's coarse shift about its neighbour's", gt(0) & le(100));
    v("register_smooth_rate", smooth_rate, "m/m",
      "per-keyframe refinement: sigma of the offset change per m of path", gt(0) & le(10));
    v("register_smooth_yaw_rate", smooth_yaw_rate, "rad/m",
      "per-keyframe refinement: sigma of the yaw change per m of path", gt(0) & le(1));
    v("register_refine_iterations", refine_iterations, "",
      "per-keyframe refinement iterations per distance level (0: stretches only)", in(0, 100));
  }
};

/// The offset of one stretch of a new drive: map = Rz(yaw) (p - centre) + centre + t.
struct StretchOffset {
  int drive = 0;
  double from = 0, to = 0;                           ///< m of keyframe path
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< ENU, mean of the stretch's points
  Eigen::Vector3d t = Eigen::Vector3d::Zero();       ///< m, as registered
  double yaw = 0;                                    ///< rad
  int inliers = 0;                                   ///< correspondences at the last level
  double rmse = 0;                                   ///< m, inlier RMS at the last level
  bool registered = false;  ///< enough inliers; otherwise interpolated from its neighbours
};

/// @brief Registers every stretch of each drive to the map and moves its keyframes by the
/// offsets interpolated along the keyframe path (linear between stretch centres, a [1 2 1]
/// smoothing of interior stretches); then refines a planar offset and yaw per keyframe against
/// the map (a smooth deformation: the GPS error of a georeferenced drive changes by metres
/// within 100 m, faster than stretches follow). A drive without any registered stretch is left
/// as it is.
/// @return the stretches of all drives, in drive order.
std::vector<StretchOffset> registerToMap(const VectorMap& map, std::vector<Lsm>& lsms,
                                         const RegistrationSettings& settings);

}  // namespace mapfuse::update
