#include "mapfuse/localize/frame_observations.hpp"

#include <algorithm>
#include <cmath>

#include "mapfuse/core/error.hpp"
#include "mapfuse/localize/map_index.hpp"

namespace mapfuse::localize {
namespace {

bool isAerial(CrowdClass c) {
  return c == CrowdClass::kTrafficSign || c == CrowdClass::kTrafficLight || c == CrowdClass::kPole;
}

Eigen::Matrix3d covOf(const std::vector<Eigen::Matrix3d>& covs, std::size_t i) {
  return i < covs.size() ? covs[i] : Eigen::Matrix3d::Zero();
}

/// One element's observations in a body frame (R_body_odom, the points already in it): line
/// points thinned to `spacing`, point elements by their first point, planar ones by the centre
/// with the mean point covariance (as observationsOf does for LSM elements).
void addElement(CrowdClass cls, int key, const std::vector<Eigen::Vector3d>& p,
                const std::vector<Eigen::Matrix3d>& cov, double spacing,
                std::vector<ObservedPoint>& out) {
  if (p.empty()) return;
  switch (geometryKind(cls)) {
    case GeometryKind::kLine: {
      double since = spacing;  // the first point is always kept
      for (std::size_t i = 0; i < p.size(); ++i) {
        if (i > 0) since += (p[i] - p[i - 1]).norm();
        if (since + 1e-9 < spacing && i + 1 < p.size()) continue;
        out.push_back({key, true, p[i], covOf(cov, i)});
        since = 0;
      }
      break;
    }
    case GeometryKind::kPoint: out.push_back({key, false, p[0], covOf(cov, 0)}); break;
    case GeometryKind::kPlanar: {
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
      for (std::size_t i = 0; i < p.size(); ++i) c += p[i], C += covOf(cov, i);
      out.push_back({key, false, c / double(p.size()), C / double(p.size())});
      break;
    }
  }
}

}  // namespace

DriveObservations frameObservationsOf(const vehicle::DriveData& drive,
                                      const std::vector<vehicle::RangedMarking>& markings,
                                      const Lsm& lsm, const FrameLevelSettings& s,
                                      bool use_attributes, const std::string& source) {
  if (lsm.frame != LsmFrame::kEnu || !lsm.origin)
    throw InputError(source + ": frame must be enu (run georef on lsm-build's LSM first)");
  if (lsm.keyframes.empty()) throw InputError(source + ": no keyframe");
  if (drive.drive_id != lsm.drive_id)
    throw InputError(source + ": drive '" + drive.drive_id + "' is not the LSM's drive '" +
                     lsm.drive_id + "'");
  const std::size_t n = drive.stamps.size();
  // each keyframe is a frame of the drive: its index by stamp
  std::vector<std::size_t> kf_frame;
  for (const auto& kf : lsm.keyframes) {
    const auto it = std::lower_bound(drive.stamps.begin(), drive.stamps.end(), kf.stamp - 1e-6);
    if (it == drive.stamps.end() || std::abs(*it - kf.stamp) > 1e-6)
      throw InputError(source + ": keyframe " + std::to_string(kf.id) + " (stamp " +
                       std::to_string(kf.stamp) + ") is not a frame of drive '" + drive.drive_id +
                       "': the LSM was not built from these frames");
    kf_frame.push_back(static_cast<std::size_t>(it - drive.stamps.begin()));
  }
  DriveObservations d;
  d.points.resize(n);
  std::size_t kf = 0;  // the keyframe nearest in time to frame f
  for (std::size_t f = 0; f < n; ++f) {
    while (kf + 1 < kf_frame.size() && std::abs(drive.stamps[kf_frame[kf + 1]] - drive.stamps[f]) <=
                                           std::abs(drive.stamps[kf_frame[kf]] - drive.stamps[f]))
      ++kf;
    d.ids.push_back(static_cast<int64_t>(f));
    d.stamps.push_back(drive.stamps[f]);
    // T_enu_f = T_enu_kf T_odom_kf^-1 T_odom_f: the keyframe's georeferenced pose, then odometry
    d.T_enu_body_prior.push_back(lsm.keyframes[kf].T_frame_body *
                                 drive.T_odom_body[kf_frame[kf]].inverse() * drive.T_odom_body[f]);
  }
  for (const auto& m : markings) {  // ground: each frame its own, into its body frame
    if (m.frame < 0 || static_cast<std::size_t>(m.frame) >= n) continue;
    const Pose3 T_body_odom = drive.T_odom_body[m.frame].inverse();
    const Eigen::Matrix3d& R = T_body_odom.linear();
    std::vector<Eigen::Vector3d> p;
    std::vector<Eigen::Matrix3d> cov;
    for (std::size_t i = 0; i < m.points.size(); ++i) {
      p.push_back(T_body_odom * m.points[i]);
      cov.push_back(R * covOf(m.covariances, i) * R.transpose());
    }
    addElement(m.cls, matchKey(m.cls, m.attributes, use_attributes), p, cov, s.frame_point_spacing,
               d.points[m.frame]);
  }
  for (const auto& e : lsm.elements) {  // aerial: triangulated, at their keyframe's frame
    if (!isAerial(e.cls) || e.points_body.empty()) continue;
    addElement(e.cls, matchKey(e.cls, e.attributes, use_attributes), e.points_body, e.covariances,
               s.frame_point_spacing, d.points[kf_frame[lsm.keyframeIndex(e.anchor)]]);
  }
  return d;
}

}  // namespace mapfuse::localize
