#include "mapfuse/update/map_registration.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "mapfuse/fusion/align.hpp"
#include "mapfuse/fusion/gicp.hpp"

namespace mapfuse::update {
namespace {

// Map lines are resampled to at most this spacing (m) so that a target point is always near:
// the LSMs' line points are 0.75 m apart.
constexpr double kTargetSpacing = 0.5;
// GICP convergence (m / rad per step), damping and the unobservable-direction floor: align's.
constexpr double kStepEps = 1e-3;
constexpr double kLambda = 1e-3;
constexpr double kMinInformation = 10.0;
constexpr int kMaxIterations = 20;

std::vector<Eigen::Vector3d> densified(const std::vector<Eigen::Vector3d>& pts) {
  std::vector<Eigen::Vector3d> out;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (i > 0) {
      const int n = int(std::ceil((pts[i] - pts[i - 1]).norm() / kTargetSpacing));
      for (int k = 1; k < n; ++k)
        out.push_back(pts[i - 1] + (pts[i] - pts[i - 1]) * (double(k) / n));
    }
    out.push_back(pts[i]);
  }
  return out;
}

// The map as a one-keyframe LSM in its ENU frame (body = ENU), so that fusion::elementCloud
// gives its registration cloud with the same labels and geometry covariances as the drives'.
fusion::Cloud mapCloud(const VectorMap& map) {
  Lsm lsm;
  lsm.frame = LsmFrame::kEnu;
  lsm.origin = map.origin;
  lsm.keyframes.resize(1);
  for (const MapInstance& m : map.instances) {
    Element e;
    e.id = int64_t(lsm.elements.size());
    e.cls = m.cls;
    e.attributes = m.attributes;
    e.points_body = geometryKind(m.cls) == GeometryKind::kLine ? densified(m.points) : m.points;
    e.covariances.assign(e.points_body.size(), Eigen::Matrix3d::Identity());
    lsm.elements.push_back(e);
  }
  return fusion::elementCloud(lsm, 0, 1);
}

// The target points within `margin` of the source's bounding box (cost by the area a drive
// covers, not by the map's size).
fusion::Cloud cropped(const fusion::Cloud& target, const fusion::Cloud& source, double margin) {
  Eigen::Vector2d lo = source.points.front().head<2>(), hi = lo;
  for (const auto& p : source.points) lo = lo.cwiseMin(p.head<2>()), hi = hi.cwiseMax(p.head<2>());
  lo.array() -= margin;
  hi.array() += margin;
  fusion::Cloud out;
  for (std::size_t i = 0; i < target.size(); ++i) {
    const Eigen::Vector2d q = target.points[i].head<2>();
    if ((q.array() < lo.array()).any() || (q.array() > hi.array()).any()) continue;
    out.points.push_back(target.points[i]);
    out.covariances.push_back(target.covariances[i]);
    out.labels.push_back(target.labels[i]);
  }
  return out;
}

std::vector<double> pathLength(const Lsm& lsm) {
  std::vector<double> s(lsm.keyframes.size(), 0.0);
  for (std::size_t k = 1; k < s.size(); ++k)
    s[k] = s[k - 1] + (lsm.keyframes[k].T_frame_body.translation() -
                       lsm.keyframes[k - 1].T_frame_body.translation())
                          .norm();
  return s;
}

// One stretch registered to the map: semantic GICP over the coarse-to-fine distances, the
// result as a translation of the stretch's centre and a yaw about it (roll and pitch, which
// flat road markings hardly constrain, are left to georef).
void registerStretch(const fusion::Cloud& map_cloud, const fusion::Cloud& source,
                     const RegistrationSettings& s, StretchOffset& out) {
  if (source.size() < std::size_t(s.min_inliers)) return;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& p : source.points) c += p;
  out.centre = c / double(source.size());
  const double reach = *std::max_element(s.distances.begin(), s.distances.end());
  const fusion::Cloud target = cropped(map_cloud, source, reach + 1.0);
  if (target.size() < std::size_t(s.min_inliers)) return;
  Pose3 delta = Pose3::Identity();
  fusion::GicpResult r;
  for (double dist : s.distances) {
    fusion::GicpSettings g;
    g.max_correspondence_distance = dist;
    g.max_iterations = kMaxIterations;
    g.translation_eps = g.rotation_eps = kStepEps;
    g.same_label_only = true;
    g.lambda = kLambda;
    g.huber_delta = s.huber;
    g.min_information = kMinInformation;
    const fusion::GicpTarget index(target, 2.0 * dist);
    r = fusion::alignGicp(index, source, delta, g);
    if (r.num_inliers < s.min_inliers) return;
    delta = r.T_target_source;
  }
  out.inliers = r.num_inliers;
  out.rmse = r.rmse;
  out.registered = true;
  const Eigen::Matrix3d R = delta.linear();
  out.yaw = std::atan2(R(1, 0), R(0, 0));
  out.t = delta * out.centre - out.centre;
}

// [1 2 1] / 4 over runs of three registered stretches (exact on an offset drifting linearly).
void smooth(std::vector<StretchOffset>& st) {
  const std::vector<StretchOffset> raw = st;
  for (std::size_t j = 1; j + 1 < st.size(); ++j) {
    if (!raw[j - 1].registered || !raw[j].registered || !raw[j + 1].registered) continue;
    st[j].t = 0.25 * raw[j - 1].t + 0.5 * raw[j].t + 0.25 * raw[j + 1].t;
    st[j].yaw = 0.25 * raw[j - 1].yaw + 0.5 * raw[j].yaw + 0.25 * raw[j + 1].yaw;
  }
}

// The offset at path length `at`: linear between the centres of the registered stretches,
// extended linearly beyond the first and last (at most half a stretch).
StretchOffset offsetAt(const std::vector<const StretchOffset*>& reg, double at) {
  if (reg.size() == 1) return *reg[0];
  std::size_t j = 1;
  while (j + 1 < reg.size() && 0.5 * (reg[j]->from + reg[j]->to) < at) ++j;
  const StretchOffset& a = *reg[j - 1];
  const StretchOffset& b = *reg[j];
  const double sa = 0.5 * (a.from + a.to), sb = 0.5 * (b.from + b.to);
  const double w = (at - sa) / (sb - sa);
  StretchOffset o = a;
  o.centre = a.centre + w * (b.centre - a.centre);
  o.t = a.t + w * (b.t - a.t);
  o.yaw = a.yaw + w * (b.yaw - a.yaw);
  return o;
}

// Moves every keyframe by the offset at its path length: T <- D T, D = [Rz, c + t - Rz c].
void applyOffsets(const std::vector<StretchOffset>& st, const std::vector<double>& s, Lsm& lsm) {
  std::vector<const StretchOffset*> reg;
  for (const auto& o : st)
    if (o.registered) reg.push_back(&o);
  if (reg.empty()) return;
  for (std::size_t k = 0; k < lsm.keyframes.size(); ++k) {
    const StretchOffset o = offsetAt(reg, s[k]);
    Pose3 D = Pose3::Identity();
    D.linear() = Eigen::AngleAxisd(o.yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    D.translation() = o.centre + o.t - D.linear() * o.centre;
    lsm.keyframes[k].T_frame_body = D * lsm.keyframes[k].T_frame_body;
  }
}

std::vector<StretchOffset> registerDrive(const fusion::Cloud& map_cloud, int drive, Lsm& lsm,
                                         const RegistrationSettings& s) {
  const std::vector<double> path = pathLength(lsm);
  const double total = path.empty() ? 0.0 : path.back();
  const int n = std::max(1, int(std::lround(total / s.stretch_length)));
  std::vector<StretchOffset> st(n);
  std::size_t kb = 0;
  for (int j = 0; j < n; ++j) {
    StretchOffset& o = st[j];
    o.drive = drive;
    o.from = total * j / n;
    o.to = total * (j + 1) / n;
    std::size_t ke = kb;
    while (ke < path.size() && (j == n - 1 || path[ke] < o.to)) ++ke;
    if (ke > kb) registerStretch(map_cloud, fusion::elementCloud(lsm, int(kb), int(ke)), s, o);
    kb = ke;
  }
  smooth(st);
  applyOffsets(st, path, lsm);
  return st;
}

}  // namespace

std::vector<StretchOffset> registerToMap(const VectorMap& map, std::vector<Lsm>& lsms,
                                         const RegistrationSettings& settings) {
  std::vector<StretchOffset> out;
  if (!settings.enabled || map.instances.empty()) return out;
  const fusion::Cloud map_cloud = mapCloud(map);
  for (std::size_t d = 0; d < lsms.size(); ++d) {
    const auto st = registerDrive(map_cloud, int(d), lsms[d], settings);
    out.insert(out.end(), st.begin(), st.end());
  }
  return out;
}

}  // namespace mapfuse::update
