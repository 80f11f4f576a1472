#include "drive_view.hpp"

#include <Eigen/Geometry>
#include <cmath>

#include "mapfuse/core/voxel_grid.hpp"

namespace mapfuse::update {

int64_t DriveView::key(double x, double y) const {
  return voxel_grid::cellKey2d(x, y, cell_);
}

DriveView::DriveView(const Lsm& lsm, const ViewSettings& settings, double min_confidence)
    : s_(settings) {
  // The camera fires between keyframes too (several metres apart; in a turn the heading
  // changes by tens of degrees between two): poses interpolated every pose_step m.
  auto add = [&](const Pose3& T) {
    grid_[key(T.translation().x(), T.translation().y())].push_back(int(body_from_enu_.size()));
    body_from_enu_.push_back(T.inverse());
  };
  for (std::size_t k = 0; k < lsm.keyframes.size(); ++k) {
    const Pose3& T = lsm.keyframes[k].T_frame_body;
    if (k > 0) {
      const Pose3& P = lsm.keyframes[k - 1].T_frame_body;
      const int n = int(std::ceil((T.translation() - P.translation()).norm() / s_.pose_step));
      const Eigen::Quaterniond qa(P.linear()), qb(T.linear());
      for (int i = 1; i < n; ++i) {
        const double w = double(i) / n;
        Pose3 M = Pose3::Identity();
        M.linear() = qa.slerp(w, qb).toRotationMatrix();
        M.translation() = (1 - w) * P.translation() + w * T.translation();
        add(M);
      }
    }
    add(T);
  }
  // Where the drive looked: its observations of confidence >= min_confidence (ground markings
  // enter an LSM only where the ground was ranged, near the car; a corner the camera swept past
  // in a turn holds none).
  if (s_.coverage_radius > 0)
    for (const Element& e : lsm.elements) {
      if (e.confidence < min_confidence) continue;
      for (const auto& q : lsm.pointsInFrame(e))
        covered_[voxel_grid::cellKey2d(q.x(), q.y(), s_.coverage_radius)].push_back(q.head<2>());
    }
}

bool DriveView::covered(const Eigen::Vector3d& p) const {
  if (s_.coverage_radius <= 0) return true;
  const double r = s_.coverage_radius;
  const int64_t cx = int64_t(std::floor(p.x() / r)), cy = int64_t(std::floor(p.y() / r));
  for (int64_t dx = -1; dx <= 1; ++dx)
    for (int64_t dy = -1; dy <= 1; ++dy) {
      const auto it = covered_.find(voxel_grid::cellKey2d(cx + dx, cy + dy));
      if (it == covered_.end()) continue;
      for (const auto& q : it->second)
        if ((q - p.head<2>()).squaredNorm() <= r * r) return true;
    }
  return false;
}

bool DriveView::sees(const Eigen::Vector3d& p) const {
  const double reach = s_.camera_x + s_.max_range;  // farthest keyframe that can see p
  const int n = int(std::ceil(reach / cell_));
  const double lo = s_.min_range + s_.view_margin, hi = s_.max_range - s_.view_margin;
  const double lateral = s_.lateral_range - s_.view_margin;
  for (int dx = -n; dx <= n; ++dx)
    for (int dy = -n; dy <= n; ++dy) {
      const auto it = grid_.find(key(p.x() + dx * cell_, p.y() + dy * cell_));
      if (it == grid_.end()) continue;
      for (int k : it->second) {
        const Eigen::Vector3d b = body_from_enu_[k] * p;
        const double x = b.x() - s_.camera_x;
        const double r = std::hypot(x, b.y());
        if (r < lo || r > hi || std::abs(b.y()) > lateral || x <= 0) continue;
        // the field of view shrunk by the margin at this range
        if (std::abs(std::atan2(b.y(), x)) <= s_.half_fov - s_.view_margin / r) return covered(p);
      }
    }
  return false;
}

}  // namespace mapfuse::update
