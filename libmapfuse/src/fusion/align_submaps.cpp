// Align stage 1 inputs: element clouds, submaps and the choice of submap pairs to register.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <map>

#include "align_internal.hpp"
#include "mapfuse/fusion/voxel_hash.hpp"

namespace mapfuse::fusion {

namespace {
constexpr double kFreeSigma = 10.0;  // m, "free" direction (point-to-line behaviour)
constexpr double kEndSigma = 0.3;    // m, along a dash / stop line or in a polygon's plane
// Covariance with sigma `along` along unit direction d and `across` perpendicular to it.
Eigen::Matrix3d lineCov(const Eigen::Vector3d& d, double along, double across) {
  const Eigen::Matrix3d P = d * d.transpose();
  return along * along * P + across * across * (Eigen::Matrix3d::Identity() - P);
}
// Sigma `in_plane` in the plane with normal n, `normal` along n.
Eigen::Matrix3d planeCov(const Eigen::Vector3d& n, double in_plane, double normal) {
  const Eigen::Matrix3d P = n * n.transpose();
  return in_plane * in_plane * (Eigen::Matrix3d::Identity() - P) + normal * normal * P;
}
Eigen::Vector3d planeNormal(const std::vector<Eigen::Vector3d>& pts) {
  if (pts.size() < 3) return Eigen::Vector3d::UnitZ();
  Eigen::Vector3d m = Eigen::Vector3d::Zero();
  for (const auto& p : pts) m += p;
  m /= double(pts.size());
  Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
  for (const auto& p : pts) C += (p - m) * (p - m).transpose();
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(C).eigenvectors().col(0);
}
}  // namespace

namespace detail {

int alignLabel(const Element& e) {
  if (e.cls == CrowdClass::kLaneLine && e.attributes.style == LineStyle::kDashed)
    return kLabelDashedLine;
  return int(e.cls);
}

std::vector<double> labelWeights(const std::vector<double>& class_weights) {
  std::vector<double> w(kNumAlignLabels, 1.0);
  for (int c = 0; c < kNumCrowdClasses && c < int(class_weights.size()); ++c)
    w[c] = class_weights[c];
  w[kLabelDashedLine] = w[int(CrowdClass::kLaneLine)];
  return w;
}

}  // namespace detail

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
    const auto label = uint8_t(detail::alignLabel(e));
    // Solid lines are cut at keyframe boundaries, so their ends mean nothing: free along the
    // line. Dashes and stop lines are whole elements whose ends are real: nearly isotropic.
    const bool solid_line = kind == GeometryKind::kLine && e.cls == CrowdClass::kLaneLine &&
                            e.attributes.style != LineStyle::kDashed;
    const double along = solid_line ? kFreeSigma : kEndSigma;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      Eigen::Matrix3d C;
      if (kind == GeometryKind::kLine && pts.size() >= 2) {
        const std::size_t a = i == 0 ? 0 : i - 1, b = std::min(pts.size() - 1, i + 1);
        C = lineCov((pts[b] - pts[a]).normalized(), along, sigma);
      } else if (kind == GeometryKind::kPlanar) {
        C = planeCov(n, kEndSigma, sigma);  // polygon corners: located in the plane too
      } else {                              // pole / light base point: free vertically
        C = lineCov(Eigen::Vector3d::UnitZ(), kFreeSigma, sigma);
      }
      c.points.push_back(pts[i]);
      c.covariances.push_back(C);
      c.labels.push_back(label);
    }
  }
  return c;
}

namespace detail {

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
        Submap s;
        s.lsm = l;
        s.kf_begin = begin;
        s.kf_end = k;
        s.anchor = (begin + k - 1) / 2;
        s.cloud = elementCloud(lsms[l], begin, k);
        if (s.cloud.size() >= 10) {
          s.coarse = voxelDownsample(s.cloud, 1.0);
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

std::vector<SubmapPair> selectPairs(const std::vector<Submap>& maps, const AlignSettings& s) {
  const int n = int(maps.size());
  const double r = s.overlap_radius;
  // One coarse index per submap (label folded into the key by a large z offset).
  std::vector<VoxelIndex> index(n);
  auto lift = [](const Eigen::Vector3d& p, int label) {
    return Eigen::Vector3d(p.x(), p.y(), p.z() + 1000.0 * label);
  };
#pragma omp parallel for schedule(dynamic) num_threads(s.threads)
  for (int i = 0; i < n; ++i) {
    std::vector<Eigen::Vector3d> pts;
    for (std::size_t k = 0; k < maps[i].coarse.size(); ++k)
      pts.push_back(lift(maps[i].coarse.points[k], maps[i].coarse.labels[k]));
    index[i] = VoxelIndex(pts, r);
  }
  // Candidate pairs: boxes within the radius, different LSMs.
  std::vector<std::pair<int, int>> cand;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      if (maps[i].lsm == maps[j].lsm) continue;
      if (((maps[i].lo.array() - r) <= maps[j].hi.array()).all() &&
          ((maps[j].lo.array() - r) <= maps[i].hi.array()).all())
        cand.emplace_back(i, j);
    }
  // Overlap, symmetric: the smaller of the two directed shares.
  std::vector<double> ov(cand.size(), 0.0);
  auto share = [&](int from, int to) {
    const Cloud& c = maps[from].coarse;
    int near = 0;
    for (std::size_t k = 0; k < c.size(); ++k)
      near += index[to].nearest(lift(c.points[k], c.labels[k]), r * r, nullptr) >= 0;
    return double(near) / double(std::max<std::size_t>(1, c.size()));
  };
#pragma omp parallel for schedule(dynamic, 16) num_threads(s.threads)
  for (int p = 0; p < int(cand.size()); ++p)
    ov[p] = std::min(share(cand[p].first, cand[p].second), share(cand[p].second, cand[p].first));
  // Per submap, the best partner of each other LSM, then the max_partners best of those, or
  // (spread_partners) max_partners of those evenly spread over the LSMs, the offset rotating with
  // the submap: drives whose GPS biases agree overlap best in georef's ENU, so "best" ties like
  // to like and can leave groups of drives joined only elsewhere.
  std::vector<std::map<int, std::pair<double, int>>> best(n);  // submap -> lsm -> (overlap, pair)
  for (int p = 0; p < int(cand.size()); ++p) {
    if (ov[p] < s.min_overlap) continue;
    const auto [i, j] = cand[p];
    for (const auto& [self, other] : {std::pair{i, j}, std::pair{j, i}}) {
      auto& slot = best[self][maps[other].lsm];
      if (ov[p] > slot.first) slot = {ov[p], p};
    }
  }
  std::vector<char> chosen(cand.size(), 0);
  for (int i = 0; i < n; ++i) {
    std::vector<std::pair<double, int>> v;
    for (const auto& [lsm, e] : best[i]) v.push_back(e);  // in LSM order
    const int m = int(v.size());
    const int take = s.max_partners > 0 ? std::min(s.max_partners, m) : m;
    if (s.spread_partners) {
      for (int k = 0; k < take; ++k) chosen[v[(i + k * m / take) % m].second] = 1;
      continue;
    }
    std::sort(v.begin(), v.end(), [](const auto& x, const auto& y) {
      return x.first != y.first ? x.first > y.first : x.second < y.second;
    });
    for (int k = 0; k < take; ++k) chosen[v[k].second] = 1;
  }
  std::vector<SubmapPair> out;
  for (int p = 0; p < int(cand.size()); ++p) {
    if (!chosen[p]) continue;
    auto [i, j] = cand[p];
    if (maps[i].lsm > maps[j].lsm) std::swap(i, j);
    out.push_back({i, j, ov[p]});
  }
  return out;
}

}  // namespace detail
}  // namespace mapfuse::fusion
