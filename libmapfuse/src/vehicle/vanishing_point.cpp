#include "mapfuse/vehicle/vanishing_point.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

#include "mapfuse/vehicle/ground_ranging.hpp"

namespace mapfuse::vehicle {
namespace {
/// m, lane observations whose lateral offsets differ less belong to one line (lanes are ~3.5 m
/// apart, a dashed line's dashes share one offset).
constexpr double kLaneGroupGap = 0.8;
}  // namespace

std::optional<ImageLine> fitImageLine(const std::vector<Eigen::Vector2d>& pixels) {
  if (pixels.size() < 2) return std::nullopt;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : pixels) mean += p;
  mean /= double(pixels.size());
  Eigen::Matrix2d S = Eigen::Matrix2d::Zero();
  for (const auto& p : pixels) S += (p - mean) * (p - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(S);
  const Eigen::Vector2d normal = es.eigenvectors().col(0);  // smallest eigenvalue
  ImageLine line;
  line.l = Eigen::Vector3d(normal.x(), normal.y(), -normal.dot(mean));
  line.rms = std::sqrt(std::max(0.0, es.eigenvalues()(0)) / double(pixels.size()));
  return line;
}

std::optional<Eigen::Vector3d> vanishingPoint(const std::vector<ImageLine>& lines,
                                              double min_line_angle) {
  if (lines.size() < 2) return std::nullopt;
  // Require at least one pair of lines with distinct image directions.
  double max_angle = 0.0;
  for (std::size_t i = 0; i < lines.size(); ++i)
    for (std::size_t j = i + 1; j < lines.size(); ++j) {
      const double c = std::abs(lines[i].l.head<2>().dot(lines[j].l.head<2>()));
      max_angle = std::max(max_angle, std::acos(std::min(1.0, c)));
    }
  if (max_angle < min_line_angle) return std::nullopt;
  Eigen::MatrixXd A(lines.size(), 3);
  for (std::size_t i = 0; i < lines.size(); ++i) A.row(i) = lines[i].l.transpose();
  // Condition the problem: scale pixel coordinates so that the third column is comparable.
  const double s = 1000.0;
  A.col(2) /= s;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  Eigen::Vector3d v = svd.matrixV().col(2);
  v.z() /= s;
  return v;
}

std::optional<double> pitchFromVanishingDirection(const Eigen::Vector3d& n,
                                                  const Eigen::Vector3d& d) {
  // (R_x(t) n)^T d = C + A cos t + B sin t = 0.
  const double A = d.y() * n.y() + d.z() * n.z();
  const double B = d.z() * n.y() - d.y() * n.z();
  const double C = n.x() * d.x();
  const double R = std::hypot(A, B);
  if (R < 1e-12 || std::abs(C) > R) return std::nullopt;
  const double phi = std::atan2(B, A);
  const double delta = std::acos(-C / R);
  auto wrap = [](double a) { return std::atan2(std::sin(a), std::cos(a)); };
  const double t1 = wrap(phi + delta), t2 = wrap(phi - delta);
  return std::abs(t1) < std::abs(t2) ? t1 : t2;
}

std::optional<VanishingEstimate> estimateVanishing(
    const std::vector<std::vector<Eigen::Vector2d>>& lane_pixels, const Eigen::Matrix3d& K,
    const GroundPlane& nominal, const VanishingSettings& s) {
  std::vector<ImageLine> lines;
  for (const auto& poly : lane_pixels) {
    if (int(poly.size()) < s.min_points_per_line) continue;
    const auto line = fitImageLine(poly);
    if (line && line->rms <= s.max_line_rms) lines.push_back(*line);
  }
  const auto v = vanishingPoint(lines, s.min_line_angle);
  if (!v) return std::nullopt;
  Eigen::Vector3d d = K.inverse() * *v;
  if (d.norm() < 1e-12) return std::nullopt;
  d.normalize();
  if (d.z() < 0.0) d = -d;  // lanes recede in front of the camera
  const auto pitch = pitchFromVanishingDirection(nominal.normal_cam, d);
  if (!pitch || std::abs(*pitch) > s.max_pitch_correction) return std::nullopt;
  return VanishingEstimate{*pitch, d, int(lines.size())};
}

std::optional<double> estimatePitchCorrection(
    const std::vector<std::vector<Eigen::Vector2d>>& lane_pixels, const Eigen::Matrix3d& K,
    const GroundPlane& nominal, const VanishingSettings& s) {
  const auto e = estimateVanishing(lane_pixels, K, nominal, s);
  if (!e) return std::nullopt;
  return e->pitch;
}

std::vector<std::vector<Eigen::Vector2d>> laneLinePixels(const FrameObservations& frame,
                                                         const Eigen::Matrix3d& K_inv,
                                                         const GroundPlane& nominal,
                                                         double min_range, double max_range) {
  std::vector<std::pair<double, std::vector<Eigen::Vector2d>>> obs;  // (lateral offset, pixels)
  for (const auto& g : frame.ground) {
    if (g.cls != CrowdClass::kLaneLine) continue;
    std::vector<Eigen::Vector2d> near;
    std::vector<double> lateral;
    for (const auto& px : g.pixels) {
      const auto X = backProjectToGround(px, K_inv, nominal);
      if (!X || X->norm() < min_range || X->norm() > max_range) continue;
      near.push_back(px);
      lateral.push_back(X->x() * std::max(0.2, 15.0 / X->norm()));  // shrink far distortion
    }
    if (near.empty()) continue;
    std::nth_element(lateral.begin(), lateral.begin() + lateral.size() / 2, lateral.end());
    obs.push_back({lateral[lateral.size() / 2], std::move(near)});
  }
  std::sort(obs.begin(), obs.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::vector<Eigen::Vector2d>> lanes;
  for (std::size_t k = 0; k < obs.size(); ++k) {
    if (k == 0 || obs[k].first - obs[k - 1].first > kLaneGroupGap) lanes.emplace_back();
    lanes.back().insert(lanes.back().end(), obs[k].second.begin(), obs[k].second.end());
  }
  return lanes;
}

std::optional<Eigen::Vector3d> normalFromTwoDirections(const Eigen::Vector3d& d1,
                                                       const Eigen::Vector3d& d2,
                                                       const Eigen::Vector3d& nominal) {
  Eigen::Vector3d n = d1.normalized().cross(d2.normalized());
  if (n.norm() < 0.2) return std::nullopt;  // < ~11.5 degrees apart
  n.normalize();
  if (n.dot(nominal) < 0.0) n = -n;
  return n;
}

std::vector<double> smoothCorrections(const std::vector<std::optional<double>>& per_frame,
                                      int window) {
  const int n = int(per_frame.size());
  const int half = std::max(0, window / 2);
  std::vector<double> out(n, 0.0);
  std::vector<double> buf;
  for (int i = 0; i < n; ++i) {
    buf.clear();
    for (int j = std::max(0, i - half); j <= std::min(n - 1, i + half); ++j)
      if (per_frame[j]) buf.push_back(*per_frame[j]);
    if (buf.empty()) {
      // Widen until something is found (frames without lanes keep the nearest estimate).
      for (int r = half + 1; r < n && buf.empty(); ++r) {
        if (i - r >= 0 && per_frame[i - r]) buf.push_back(*per_frame[i - r]);
        if (i + r < n && per_frame[i + r]) buf.push_back(*per_frame[i + r]);
      }
    }
    if (buf.empty()) continue;
    std::nth_element(buf.begin(), buf.begin() + buf.size() / 2, buf.end());
    out[i] = buf[buf.size() / 2];
  }
  return out;
}

}  // namespace mapfuse::vehicle
