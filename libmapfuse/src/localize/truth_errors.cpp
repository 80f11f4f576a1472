#include "mapfuse/localize/truth_errors.hpp"

#include <cmath>

#include "mapfuse/core/error.hpp"
#include "mapfuse/geo/origin.hpp"

namespace mapfuse::localize {
namespace {

constexpr double kDeg = 180.0 / M_PI;

void add(MeanAbsError& m, const PlanarError& e) {
  m.lateral += std::abs(e.lateral);
  m.longitudinal += std::abs(e.longitudinal);
  m.heading_deg += std::abs(e.heading_deg);
  ++m.count;
}

void finish(MeanAbsError& m) {
  if (m.count == 0) return;
  m.lateral /= m.count;
  m.longitudinal /= m.count;
  m.heading_deg /= m.count;
}

}  // namespace

PlanarError planarError(const Pose3& T_est, const Pose3& T_true) {
  const Eigen::Matrix3d& R = T_true.linear();
  const double yaw_true = std::atan2(R(1, 0), R(0, 0));
  const double yaw_est = std::atan2(T_est.linear()(1, 0), T_est.linear()(0, 0));
  const Eigen::Vector2d d = (T_est.translation() - T_true.translation()).head<2>();
  PlanarError e;
  e.enu = d;
  e.true_yaw = yaw_true;
  e.longitudinal = std::cos(yaw_true) * d.x() + std::sin(yaw_true) * d.y();
  e.lateral = -std::sin(yaw_true) * d.x() + std::cos(yaw_true) * d.y();
  e.heading_deg = std::atan2(std::sin(yaw_est - yaw_true), std::cos(yaw_est - yaw_true)) * kDeg;
  return e;
}

LocalizeErrors localizeErrors(const LocalizeResult& result, const eval::TrueTrajectory& truth,
                              const geo::GeoOrigin& origin, const std::string& source,
                              const Pose3& T_truth_map) {
  const Pose3 T_map_truth = T_truth_map.inverse();
  const bool convert = !geo::sameOrigin(origin, truth.origin);
  const geo::EnuConverter from(truth.origin), to(origin);
  const auto sorted = eval::sortedByStamp(truth);
  LocalizeErrors out;
  for (const auto& k : result.keyframes) {
    const auto t = eval::truePoseAt(sorted, k.stamp);
    if (!t) continue;
    const Pose3 T_true = convert ? geo::reexpressPose(*t, from, to) : *t;
    KeyframeError e;
    e.id = k.id;
    e.distance = k.distance;
    e.lost = k.status == KeyframeStatus::kLost;
    e.localized = planarError(k.T_enu_body, T_true);
    e.prior = planarError(k.T_enu_prior, T_true);
    e.in_map = planarError(k.T_enu_body, T_map_truth * T_true);
    if (!e.lost) {
      add(out.localized, e.localized);
      add(out.prior, e.prior);
      add(out.in_map, e.in_map);
    }
    out.keyframes.push_back(e);
  }
  if (out.keyframes.empty() && !result.keyframes.empty())
    throw InputError(source + ": no keyframe stamp inside the true trajectory of drive '" +
                     truth.drive_id + "'");
  finish(out.localized);
  finish(out.prior);
  finish(out.in_map);
  return out;
}

MeanAbsError pooled(const std::vector<LocalizeErrors>& drives, ErrorOf which) {
  MeanAbsError m;
  for (const auto& d : drives)
    for (const auto& e : d.keyframes)
      if (!e.lost)
        add(m, which == ErrorOf::kPrior   ? e.prior
               : which == ErrorOf::kInMap ? e.in_map
                                          : e.localized);
  finish(m);
  return m;
}

Eigen::Vector2d commonOffset(const std::vector<LocalizeErrors>& drives) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  int n = 0;
  for (const auto& d : drives)
    for (const auto& e : d.keyframes)
      if (!e.lost) sum += e.localized.enu, ++n;
  return n ? Eigen::Vector2d(sum / n) : sum;
}

MeanAbsError pooledWithoutOffset(const std::vector<LocalizeErrors>& drives,
                                 const Eigen::Vector2d& offset) {
  MeanAbsError m;
  for (const auto& d : drives)
    for (const auto& e : d.keyframes) {
      if (e.lost) continue;
      PlanarError p = e.localized;
      const Eigen::Vector2d v = p.enu - offset;
      p.longitudinal = std::cos(p.true_yaw) * v.x() + std::sin(p.true_yaw) * v.y();
      p.lateral = -std::sin(p.true_yaw) * v.x() + std::cos(p.true_yaw) * v.y();
      add(m, p);
    }
  finish(m);
  return m;
}

}  // namespace mapfuse::localize
