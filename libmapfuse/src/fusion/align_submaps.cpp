// Align stage 1 inputs: element clouds, submaps and the choice of submap pairs to register.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <map>
#include <tuple>
#include <unordered_map>

#include "align_internal.hpp"
#include "mapfuse/core/parallel_for.hpp"
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

}  // namespace detail

namespace {

// Element points of the listed elements in the LSM frame, with geometry covariances (unless
// `points_only`: points and labels); of solid lane lines only every `solid_stride`-th point.
Cloud cloudOf(const Lsm& lsm, const std::vector<int>& elements, double sigma, int solid_stride,
              bool points_only = false) {
  Cloud c;
  for (int ei : elements) {
    const Element& e = lsm.elements[ei];
    const Pose3& T = lsm.keyframes[lsm.keyframeIndex(e.anchor)].T_frame_body;
    std::vector<Eigen::Vector3d> pts;
    for (const auto& p : e.points_body) pts.push_back(T * p);
    const GeometryKind kind = geometryKind(e.cls);
    const auto label = uint8_t(detail::alignLabel(e));
    if (points_only) {
      for (const auto& p : pts) {
        c.points.push_back(p);
        c.labels.push_back(label);
      }
      continue;
    }
    const Eigen::Vector3d n = kind == GeometryKind::kPlanar ? planeNormal(pts) : Eigen::Vector3d();
    // Solid lines are cut at keyframe boundaries, so their ends mean nothing: free along the
    // line. Dashes and stop lines are whole elements whose ends are real: nearly isotropic.
    const bool solid_line = kind == GeometryKind::kLine && e.cls == CrowdClass::kLaneLine &&
                            e.attributes.style != LineStyle::kDashed;
    const double along = solid_line ? kFreeSigma : kEndSigma;
    const std::size_t stride = solid_line ? std::size_t(std::max(1, solid_stride)) : 1;
    for (std::size_t i = 0; i < pts.size(); i += stride) {
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

}  // namespace

std::vector<double> labelWeights(const std::vector<double>& class_weights) {
  std::vector<double> w(kNumAlignLabels, 1.0);
  for (int c = 0; c < kNumCrowdClasses && c < int(class_weights.size()); ++c)
    w[c] = class_weights[c];
  w[kLabelDashedLine] = w[int(CrowdClass::kLaneLine)];
  return w;
}

std::vector<double> coarseVoteWeights(const AlignSettings& s) {
  std::vector<double> w = labelWeights(s.coarse_class_weights);
  const std::vector<double> wc = labelWeights(s.class_weights);
  for (std::size_t l = 0; l < w.size(); ++l) w[l] *= wc[l];
  return w;
}

Cloud elementCloud(const Lsm& lsm, int kf_begin, int kf_end, double sigma) {
  std::vector<int> elements;
  for (int i = 0; i < int(lsm.elements.size()); ++i) {
    const int k = int(lsm.keyframeIndex(lsm.elements[i].anchor));
    if (k >= kf_begin && k < kf_end) elements.push_back(i);
  }
  return cloudOf(lsm, elements, sigma, 1);
}

namespace detail {

Cloud submapCloud(const std::vector<Lsm>& lsms, const Submap& m, int solid_stride) {
  return cloudOf(lsms[m.lsm], m.elements, 0.05, solid_stride);
}

std::vector<Submap> buildSubmaps(const std::vector<Lsm>& lsms, double length, int threads) {
  // Per LSM, side by side (independent), then concatenated in LSM order.
  std::vector<std::vector<Submap>> per_lsm(lsms.size());
  parallelFor(
      lsms.size(),
      [&](std::size_t li) {
        const int l = int(li);
        const auto& kfs = lsms[l].keyframes;
        // Elements by anchor keyframe (stable: file order within a keyframe).
        std::vector<std::vector<int>> by_kf(kfs.size());
        for (int i = 0; i < int(lsms[l].elements.size()); ++i)
          by_kf[lsms[l].keyframeIndex(lsms[l].elements[i].anchor)].push_back(i);
        int begin = 0;
        double dist = 0;
        for (int k = 1; k <= int(kfs.size()); ++k) {
          if (k < int(kfs.size()))
            dist +=
                (kfs[k].T_frame_body.translation() - kfs[k - 1].T_frame_body.translation()).norm();
          if (k == int(kfs.size()) || dist >= length) {
            Submap s;
            s.lsm = l;
            s.kf_begin = begin;
            s.kf_end = k;
            s.anchor = (begin + k - 1) / 2;
            for (int kk = begin; kk < k; ++kk)
              s.elements.insert(s.elements.end(), by_kf[kk].begin(), by_kf[kk].end());
            // Points and labels only (the covariances are built when the submap is registered).
            const Cloud cloud = cloudOf(lsms[l], s.elements, 0.05, 1, /*points_only=*/true);
            if (cloud.size() >= 10) {
              s.coarse = voxelDownsample(cloud, 1.0);
              s.lo = s.hi = cloud.points[0].head<2>();
              for (const auto& p : cloud.points) {
                s.lo = s.lo.cwiseMin(p.head<2>());
                s.hi = s.hi.cwiseMax(p.head<2>());
              }
              per_lsm[li].push_back(std::move(s));
            }
            begin = k;
            dist = 0;
          }
        }
      },
      threads);
  std::vector<Submap> out;
  for (auto& v : per_lsm)
    for (auto& s : v) out.push_back(std::move(s));
  return out;
}

namespace {

constexpr double kCell = 64.0;  // m, grid cell of the submap boxes
constexpr int kProbes = 3;      // LSMs tried per partner slot (spread): the next when refused

/// A point lifted by its label (a large z offset), so that one index keys both.
Eigen::Vector3d lift(const Eigen::Vector3d& p, int label) {
  return Eigen::Vector3d(p.x(), p.y(), p.z() + 1000.0 * label);
}

/// Symmetric overlap of two submaps: the smaller of the two directed shares of coarse points
/// with a same-label neighbour within the radius, each over at most ~64 points.
class OverlapMeter {
 public:
  OverlapMeter(const std::vector<Submap>& maps, double radius, int threads)
      : maps_(maps), r_(radius), index_(maps.size()) {
    const int n = int(maps.size());
#pragma omp parallel for schedule(dynamic) num_threads(threads)
    for (int i = 0; i < n; ++i) {
      std::vector<Eigen::Vector3d> pts;
      for (std::size_t k = 0; k < maps[i].coarse.size(); ++k)
        pts.push_back(lift(maps[i].coarse.points[k], maps[i].coarse.labels[k]));
      index_[i] = VoxelIndex(pts, r_);
    }
  }
  double operator()(int i, int j) const {
    return std::min(share(i, j), share(j, i));
  }

 private:
  double share(int from, int to) const {
    const Cloud& c = maps_[from].coarse;
    const std::size_t step = std::max<std::size_t>(1, c.size() / 64);
    int near = 0, tried = 0;
    for (std::size_t k = 0; k < c.size(); k += step, ++tried)
      near += index_[to].nearest(lift(c.points[k], c.labels[k]), r_ * r_, nullptr) >= 0;
    return double(near) / double(std::max(1, tried));
  }
  const std::vector<Submap>& maps_;
  double r_;
  std::vector<VoxelIndex> index_;
};

/// Submaps by grid cell of their boxes, to find the candidates of a submap without a scan.
class BoxGrid {
 public:
  explicit BoxGrid(const std::vector<Submap>& maps) : maps_(maps) {
    for (int i = 0; i < int(maps.size()); ++i)
      for (int64_t x = cell(maps[i].lo.x()); x <= cell(maps[i].hi.x()); ++x)
        for (int64_t y = cell(maps[i].lo.y()); y <= cell(maps[i].hi.y()); ++y)
          grid_[key(x, y)].push_back(i);
  }
  /// Submaps of other LSMs whose boxes come within r of submap i's, sorted by LSM then index.
  /// `seen` (size n, reused between calls) marks what this query has visited.
  void candidates(int i, double r, std::vector<int>& seen, std::vector<int>& cand) const {
    cand.clear();
    const Submap& m = maps_[i];
    for (int64_t x = cell(m.lo.x() - r); x <= cell(m.hi.x() + r); ++x)
      for (int64_t y = cell(m.lo.y() - r); y <= cell(m.hi.y() + r); ++y) {
        const auto it = grid_.find(key(x, y));
        if (it == grid_.end()) continue;
        for (int j : it->second) {
          if (seen[j] == i || maps_[j].lsm == m.lsm) continue;
          seen[j] = i;
          if (((m.lo.array() - r) <= maps_[j].hi.array()).all() &&
              ((maps_[j].lo.array() - r) <= m.hi.array()).all())
            cand.push_back(j);
        }
      }
    std::sort(cand.begin(), cand.end(), [&](int a, int b) {
      return maps_[a].lsm != maps_[b].lsm ? maps_[a].lsm < maps_[b].lsm : a < b;
    });
  }

 private:
  static int64_t cell(double v) { return int64_t(std::floor(v / kCell)); }
  static uint64_t key(int64_t x, int64_t y) { return (uint64_t(uint32_t(x)) << 32) | uint32_t(y); }
  const std::vector<Submap>& maps_;
  std::unordered_map<uint64_t, std::vector<int>> grid_;
};

/// Submap i's partners among its candidates (sorted by LSM): per other LSM the best-overlapping
/// submap if it overlaps at least min_overlap; max_partners of them, spread over the LSMs
/// (each slot probing up to kProbes LSMs) or the best ones.
void choosePartners(int i, const std::vector<Submap>& maps, const std::vector<int>& cand,
                    const OverlapMeter& overlap, const AlignSettings& s, long& computed,
                    std::vector<SubmapPair>& out) {
  std::vector<std::pair<int, int>> groups;  // [begin, end) in cand, one per other LSM
  for (int k = 0; k < int(cand.size()); ++k)
    if (k == 0 || maps[cand[k]].lsm != maps[cand[k - 1]].lsm)
      groups.emplace_back(k, k + 1);
    else
      groups.back().second = k + 1;
  auto best = [&](int g) {
    std::pair<double, int> b{-1.0, -1};
    for (int k = groups[g].first; k < groups[g].second; ++k) {
      ++computed;
      const double ov = overlap(i, cand[k]);
      if (ov > b.first) b = {ov, cand[k]};
    }
    return b;
  };
  const int mm = int(groups.size());
  if (mm == 0) return;
  const int take = s.max_partners > 0 ? std::min(s.max_partners, mm) : mm;
  if (s.spread_partners) {
    std::vector<char> tried(mm, 0);
    for (int t = 0; t < take; ++t) {
      const int g0 = (i + t * mm / take) % mm;
      for (int u = 0; u < kProbes && u < mm; ++u) {
        const int g = (g0 + u) % mm;
        if (tried[g]) continue;
        tried[g] = 1;
        const auto [ov, j] = best(g);
        if (ov >= s.min_overlap) {
          out.push_back({std::min(i, j), std::max(i, j), ov});
          break;
        }
      }
    }
    return;
  }
  std::vector<std::pair<double, int>> v;  // every LSM's best
  for (int g = 0; g < mm; ++g) {
    const auto b = best(g);
    if (b.first >= s.min_overlap) v.push_back(b);
  }
  std::sort(v.begin(), v.end(), [](const auto& x, const auto& y) {
    return x.first != y.first ? x.first > y.first : x.second < y.second;
  });
  for (int k = 0; k < std::min(take, int(v.size())); ++k)
    out.push_back({std::min(i, v[k].second), std::max(i, v[k].second), v[k].first});
}

/// The union over submaps: LSM order within a pair, sorted, each pair once.
void uniquePairs(const std::vector<Submap>& maps, std::vector<SubmapPair>& out) {
  for (auto& p : out)
    if (maps[p.a].lsm > maps[p.b].lsm) std::swap(p.a, p.b);
  std::sort(out.begin(), out.end(), [](const SubmapPair& x, const SubmapPair& y) {
    return std::tie(x.a, x.b) < std::tie(y.a, y.b);
  });
  out.erase(std::unique(
                out.begin(), out.end(),
                [](const SubmapPair& x, const SubmapPair& y) { return x.a == y.a && x.b == y.b; }),
            out.end());
}

}  // namespace

std::vector<SubmapPair> selectPairs(const std::vector<Submap>& maps, const AlignSettings& s,
                                    long* overlaps) {
  const int n = int(maps.size());
  const OverlapMeter overlap(maps, s.overlap_radius, s.threads);
  const BoxGrid grid(maps);
  long computed = 0;
  std::vector<SubmapPair> out;
#pragma omp parallel num_threads(s.threads) reduction(+ : computed)
  {
    std::vector<int> seen(n, -1), cand;
    std::vector<SubmapPair> local;
#pragma omp for schedule(dynamic, 16)
    for (int i = 0; i < n; ++i) {
      grid.candidates(i, s.overlap_radius, seen, cand);
      choosePartners(i, maps, cand, overlap, s, computed, local);
    }
#pragma omp critical
    out.insert(out.end(), local.begin(), local.end());
  }
  if (overlaps) *overlaps = computed;
  uniquePairs(maps, out);
  return out;
}

}  // namespace detail
}  // namespace mapfuse::fusion
