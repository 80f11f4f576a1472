// Stage 1 registrations (eq. (7), Song et al. 2023): submaps, semantic pyramid, InterRPCs.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "mapfuse/core/error.hpp"
#include "mapfuse/fusion/align.hpp"
#include "mapfuse/fusion/gicp.hpp"

namespace mapfuse::fusion {

std::optional<AlignMethod> alignMethodFromName(const std::string& n) {
  if (n == "icp") return AlignMethod::kIcp;
  if (n == "sicp") return AlignMethod::kSicp;
  if (n == "sgicp") return AlignMethod::kSgicp;
  if (n == "gba_sgicp") return AlignMethod::kGbaSgicp;
  return std::nullopt;
}

const char* alignMethodName(AlignMethod m) {
  switch (m) {
    case AlignMethod::kIcp: return "icp";
    case AlignMethod::kSicp: return "sicp";
    case AlignMethod::kSgicp: return "sgicp";
    case AlignMethod::kGbaSgicp: return "gba_sgicp";
  }
  return "?";
}

namespace {
// Covariance free along unit direction d (variance 1 m^2), sigma^2 across.
Eigen::Matrix3d lineCov(const Eigen::Vector3d& d, double sigma) {
  return d * d.transpose() + sigma * sigma * (Eigen::Matrix3d::Identity() - d * d.transpose());
}
// Free in the plane with normal n, sigma^2 along n.
Eigen::Matrix3d planeCov(const Eigen::Vector3d& n, double sigma) {
  return (Eigen::Matrix3d::Identity() - n * n.transpose()) + sigma * sigma * n * n.transpose();
}
Eigen::Vector3d planeNormal(const std::vector<Eigen::Vector3d>& pts) {
  Eigen::Vector3d m = Eigen::Vector3d::Zero();
  for (const auto& p : pts) m += p;
  m /= double(pts.size());
  Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
  for (const auto& p : pts) C += (p - m) * (p - m).transpose();
  if (pts.size() < 3) return Eigen::Vector3d::UnitZ();
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(C).eigenvectors().col(0);
}
}  // namespace

Cloud elementCloud(const Lsm& lsm, int kf_begin, int kf_end, double sigma) {
  Cloud c;
  for (const Element& e : lsm.elements) {
    const int k = int(lsm.keyframeIndex(e.anchor));
    if (k < kf_begin || k >= kf_end) continue;
    const Pose3& T = lsm.keyframes[k].T_frame_body;
    std::vector<Eigen::Vector3d> pts;
    for (const auto& p : e.points_body) pts.push_back(T * p);
    const GeometryKind kind = geometryKind(e.cls);
    const Eigen::Vector3d n = kind == GeometryKind::kPlanar ? planeNormal(pts) : Eigen::Vector3d();
    for (std::size_t i = 0; i < pts.size(); ++i) {
      Eigen::Matrix3d C;
      if (kind == GeometryKind::kLine && pts.size() >= 2) {
        const std::size_t a = i == 0 ? 0 : i - 1, b = std::min(pts.size() - 1, i + 1);
        C = lineCov((pts[b] - pts[a]).normalized(), sigma);
      } else if (kind == GeometryKind::kPlanar) {
        C = planeCov(n, sigma);
      } else {  // pole / light base point: free vertically
        C = lineCov(Eigen::Vector3d::UnitZ(), sigma);
      }
      c.points.push_back(pts[i]);
      c.covariances.push_back(C);
      c.labels.push_back(uint8_t(e.cls));
    }
  }
  return c;
}

namespace {
struct Submap {
  int lsm, kf_begin, kf_end, anchor;
  Cloud cloud;
  Eigen::Vector2d lo, hi;
};

std::vector<Submap> buildSubmaps(const std::vector<Lsm>& lsms, double length) {
  std::vector<Submap> out;
  for (int l = 0; l < int(lsms.size()); ++l) {
    const auto& kfs = lsms[l].keyframes;
    int begin = 0;
    double dist = 0;
    for (int k = 1; k <= int(kfs.size()); ++k) {
      if (k < int(kfs.size()))
        dist += (kfs[k].T_frame_body.translation() - kfs[k - 1].T_frame_body.translation()).norm();
      if (k == int(kfs.size()) || dist >= length) {
        Submap s{l, begin, k, (begin + k - 1) / 2, elementCloud(lsms[l], begin, k), {}, {}};
        if (s.cloud.size() >= 10) {
          s.lo = s.hi = s.cloud.points[0].head<2>();
          for (const auto& p : s.cloud.points) {
            s.lo = s.lo.cwiseMin(p.head<2>());
            s.hi = s.hi.cwiseMax(p.head<2>());
          }
          out.push_back(std::move(s));
        }
        begin = k;
        dist = 0;
      }
    }
  }
  return out;
}
}  // namespace

std::vector<InterConstraint> registerSubmaps(const std::vector<Lsm>& lsms, const AlignSettings& s) {
  const std::vector<Submap> maps = buildSubmaps(lsms, s.submap_length);
  std::vector<std::pair<int, int>> pairs;
  const double margin = 5.0;
  for (int i = 0; i < int(maps.size()); ++i)
    for (int j = 0; j < int(maps.size()); ++j) {
      if (maps[i].lsm >= maps[j].lsm) continue;
      const bool overlap = (maps[i].lo.array() - margin <= maps[j].hi.array()).all() &&
                           (maps[j].lo.array() - margin <= maps[i].hi.array()).all();
      if (overlap) pairs.emplace_back(i, j);
    }
  const bool semantic = s.method != AlignMethod::kIcp;
  const bool gicp = s.method == AlignMethod::kSgicp || s.method == AlignMethod::kGbaSgicp;
  std::vector<InterConstraint> out(pairs.size());
  std::vector<char> keep(pairs.size(), 0);
#pragma omp parallel for schedule(dynamic) num_threads(s.threads)
  for (int p = 0; p < int(pairs.size()); ++p) {
    const Submap& A = maps[pairs[p].first];
    const Submap& B = maps[pairs[p].second];
    InterConstraint& c = out[p];
    c.lsm_a = A.lsm;
    c.kf_a = A.anchor;
    c.lsm_b = B.lsm;
    c.kf_b = B.anchor;
    {  // overlap at the initial (georeferenced) poses
      const GicpTarget probe(A.cloud, 2.0);
      int near = 0;
      for (const auto& q : B.cloud.points) near += probe.nearest(q, -1, 4.0, nullptr) >= 0;
      c.overlap = double(near) / double(B.cloud.size());
    }
    if (c.overlap < s.min_overlap) continue;
    keep[p] = 1;
    Pose3 delta = Pose3::Identity();  // maps B's ENU points onto A's
    GicpResult r;
    const int levels = int(s.pyramid_distances.size());
    for (int lvl = 0; lvl < levels; ++lvl) {
      GicpSettings g;
      g.max_correspondence_distance = s.pyramid_distances[lvl];
      g.max_iterations = s.max_iterations;
      g.same_label_only = semantic;
      g.point_to_point = !gicp;
      g.lambda = 1e-3;
      g.huber_delta = gicp ? 3.0 : 0.0;
      if (gicp) {
        // Semantic pyramid: point-like landmarks first, then lines, then everything.
        g.label_weights = s.class_weights;
        if (lvl == 0 && levels > 1)
          for (int l : {0, 1, 2, 3}) g.label_weights[l] = 0.0;
        if (lvl == 1 && levels > 2)
          for (int l : {2, 3}) g.label_weights[l] = 0.0;
      }
      const GicpTarget target(A.cloud, g.max_correspondence_distance);
      GicpResult lr = alignGicp(target, B.cloud, delta, g);
      if (lr.num_inliers >= g.min_inliers) delta = lr.T_target_source;
      c.iterations += lr.iterations;
      r = lr;
    }
    c.converged = r.converged;
    c.fitness = r.fitness;
    c.rmse = r.rmse;
    c.accepted = r.converged && r.fitness >= s.min_fitness && r.rmse <= s.max_rmse;
    // InterRPC: T_a_b = T_enu_a^-1 * delta * T_enu_b, covariance from the inverse Hessian scaled by
    // the reduced chi-square, moved into the relative frame by the adjoint.
    const Pose3& Ta = lsms[A.lsm].keyframes[A.anchor].T_frame_body;
    const Pose3& Tb = lsms[B.lsm].keyframes[B.anchor].T_frame_body;
    c.T_a_b = Ta.inverse() * delta * Tb;
    Matrix6d H = r.hessian;
    H.diagonal().array() += 1e-6;
    const double scale =
        gicp ? std::max(1.0, r.error / std::max(1, r.num_inliers - 6)) : r.rmse * r.rmse + 1e-4;
    Matrix6d cov = H.inverse() * scale;
    const Matrix6d Ad = adjoint(Tb.inverse());
    cov = Ad * cov * Ad.transpose();
    cov += diagonalCovariance(0.02, 0.001);
    c.covariance = 0.5 * (cov + cov.transpose());
  }
  std::vector<InterConstraint> kept;
  for (std::size_t p = 0; p < out.size(); ++p)
    if (keep[p]) kept.push_back(out[p]);
  return kept;
}

}  // namespace mapfuse::fusion
