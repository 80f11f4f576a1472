#include "mapfuse/localize/map_frame.hpp"

#include <Eigen/Geometry>
#include <cmath>

#include "mapfuse/core/error.hpp"
#include "matching.hpp"

namespace mapfuse::localize {
namespace {

/// The map's sample points as observations at the identity pose (no covariance of their own:
/// line_sigma / point_sigma carry the weights).
std::vector<ObservedPoint> samplesOf(const VectorMap& map, bool use_attributes, double step) {
  std::vector<ObservedPoint> out;
  for (const auto& inst : map.instances) {
    if (inst.points.empty()) continue;
    const int key = matchKey(inst.cls, inst.attributes, use_attributes);
    const Eigen::Matrix3d zero = Eigen::Matrix3d::Zero();
    switch (geometryKind(inst.cls)) {
      case GeometryKind::kLine:
        out.push_back({key, true, inst.points[0], zero});
        for (std::size_t i = 1; i < inst.points.size(); ++i) {
          const Eigen::Vector3d a = inst.points[i - 1], b = inst.points[i];
          const int pieces = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step)));
          for (int j = 1; j <= pieces; ++j)
            out.push_back({key, true, a + (b - a) * (double(j) / pieces), zero});
        }
        break;
      case GeometryKind::kPoint: out.push_back({key, false, inst.points[0], zero}); break;
      case GeometryKind::kPlanar: out.push_back({key, false, instanceCentre(inst), zero}); break;
    }
  }
  return out;
}

}  // namespace

MapToTruth estimateMapToTruth(const VectorMap& map, const MapIndex& truth,
                              const LocalizeSettings& s, double sample_step) {
  const std::vector<ObservedPoint> samples = samplesOf(map, truth.useAttributes(), sample_step);
  std::vector<detail::WorldPoint> pts;
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const auto& p : samples) {
    pts.push_back({&p, p.p_body.head<2>(), Eigen::Matrix2d::Zero()});
    centroid += p.p_body.head<2>();
  }
  MapToTruth out;
  out.points = static_cast<int>(pts.size());
  if (!pts.empty()) centroid /= double(pts.size());
  detail::SolveInput in;
  in.c = centroid;
  in.robust_scale = s.robust_scale;
  in.max_iterations = s.max_solver_iterations;
  // no prior: a negligible one keeps the problem well posed where the map is one straight road
  in.gps = {centroid, 0.0, Eigen::Vector3d(1e-6, 1e-6, 1e-6).asDiagonal()};
  Eigen::Vector3d total = Eigen::Vector3d::Zero();  // the composed correction about the centroid
  double sum_sq = 0;
  for (int r = 0; r < s.rounds; ++r) {
    const double a = s.rounds > 1 ? double(r) / double(s.rounds - 1) : 1.0;
    const double radius = s.match_radius + a * (s.final_match_radius - s.match_radius);
    in.matches = detail::matchPoints(truth, pts, radius, s, &sum_sq);
    if (r == 0) {
      double ss0 = 0;
      const auto m0 = detail::matchPoints(truth, pts, s.final_match_radius, s, &ss0);
      out.rms_before = m0.empty() ? 0.0 : std::sqrt(ss0 / double(m0.size()));
    }
    if (in.matches.size() < 3)
      throw InputError(
          "localize: the map and the truth map share fewer than 3 matched points: "
          "no map-to-truth transform");
    const detail::SolveOutput o = detail::solvePlanarCorrection(in);
    for (auto& wp : pts) wp.q = detail::applyCorrection(o.x, centroid, wp.q);
    // both corrections rotate about the centroid: they compose by adding the angles and
    // rotating the first shift
    total = Eigen::Vector3d((Eigen::Rotation2Dd(o.x.z()) * total.head<2>() + o.x.head<2>()).x(),
                            (Eigen::Rotation2Dd(o.x.z()) * total.head<2>() + o.x.head<2>()).y(),
                            total.z() + o.x.z());
  }
  const auto final = detail::matchPoints(truth, pts, s.final_match_radius, s, &sum_sq);
  out.matched = static_cast<int>(final.size());
  out.rms_after = final.empty() ? 0.0 : std::sqrt(sum_sq / double(final.size()));
  out.dx = total.x();
  out.dy = total.y();
  out.yaw_deg = total.z() * 180.0 / M_PI;
  // q' = c + d + R (q - c)  ->  T = [R, c + d - R c]
  const Eigen::Matrix2d R = Eigen::Rotation2Dd(total.z()).toRotationMatrix();
  out.T_truth_map = Pose3::Identity();
  out.T_truth_map.linear().topLeftCorner<2, 2>() = R;
  out.T_truth_map.translation().head<2>() = centroid + total.head<2>() - R * centroid;
  return out;
}

}  // namespace mapfuse::localize
