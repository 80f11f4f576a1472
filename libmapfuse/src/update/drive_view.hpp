#pragma once
/// @file The expected observation area of one drive (docs/update.md): the union over its
/// keyframes (and poses interpolated between them) of the camera footprint, a range band and a
/// field of view in the body frame.
#include <Eigen/Core>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "mapfuse/core/lsm.hpp"
#include "mapfuse/update/change_detection.hpp"

namespace mapfuse::update {

class DriveView {
 public:
  DriveView(const Lsm& lsm, const ViewSettings& settings, double min_confidence);
  /// @brief True when some pose had the ENU point inside its shrunk camera footprint and the
  /// drive observed something (any class) within view_coverage_radius of it.
  bool sees(const Eigen::Vector3d& p) const;

 private:
  std::vector<Pose3> body_from_enu_;  ///< inverse keyframe poses and poses between them
  std::unordered_map<int64_t, std::vector<int>> grid_;
  /// observed points (confidence >= min_confidence) by cell of the coverage radius
  std::unordered_map<int64_t, std::vector<Eigen::Vector2d>> covered_;
  ViewSettings s_;
  double cell_ = 20.0;
  int64_t key(double x, double y) const;
  bool covered(const Eigen::Vector3d& p) const;
};

}  // namespace mapfuse::update
