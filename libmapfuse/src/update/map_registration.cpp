#include "mapfuse/update/map_registration.hpp"

#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>

#include "mapfuse/fusion/align.hpp"
#include "mapfuse/fusion/displacement_vote.hpp"
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

// The coarse level (fusion/displacement_vote.hpp) with align's defaults: a new drive's GPS error
// (1-4 m) exceeds half a lane width, where GICP alone would lock onto the neighbouring line.
const fusion::AlignSettings kCoarse{};

// A stretch of a new drive: its cloud, its centre and its displacement votes against the map.
struct StretchCloud {
  fusion::Cloud cloud;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  fusion::DisplacementVotes votes;
};

StretchCloud stretchCloud(const fusion::Cloud& map_cloud, fusion::Cloud source,
                          const std::vector<double>& w) {
  StretchCloud sc;
  sc.cloud = std::move(source);
  if (sc.cloud.size() == 0) return sc;
  for (const auto& p : sc.cloud.points) sc.centre += p;
  sc.centre /= double(sc.cloud.size());
  sc.votes = fusion::voteDisplacements(
      fusion::voxelDownsample(cropped(map_cloud, sc.cloud, kCoarse.coarse_radius + 1.0), 1.0),
      fusion::voxelDownsample(sc.cloud, 1.0), w, kCoarse.coarse_radius, kCoarse.coarse_bin);
  return sc;
}

// One stretch registered to the map: the coarse shift from its votes (summed with half its
// neighbours': the GPS error changes slowly along a drive, and more road directions and
// landmarks remove lane and dash aliases), then semantic GICP over the coarse-to-fine distances;
// the result as a translation of the stretch's centre and a yaw about it (roll and pitch, which
// flat road markings hardly constrain, are left to georef).
void registerStretch(const fusion::Cloud& map_cloud, const StretchCloud& sc,
                     const Eigen::Vector2d& shift, const RegistrationSettings& s,
                     StretchOffset& out) {
  const fusion::Cloud& source = sc.cloud;
  if (source.size() < std::size_t(s.min_inliers)) return;
  out.centre = sc.centre;
  const double reach = *std::max_element(s.distances.begin(), s.distances.end());
  Pose3 delta = Pose3::Identity();
  delta.translation().head<2>() = shift;
  const fusion::Cloud target =
      cropped(map_cloud, fusion::transformCloud(source, delta), reach + 1.0);
  if (target.size() < std::size_t(s.min_inliers)) return;
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

// Per-keyframe refinement. Unknowns x_k = (dx, dy, yaw) per keyframe k; a point p anchored at
// keyframe k (position c_k) moves to p + d_k + yaw_k J (p - c_k), J the 90-degree turn. Cost:
// sum over correspondences (nearest same-label map point within the level's distance) of the
// robust (Geman-McClure) planar GICP residual, whitened by the two points' covariances, plus a
// random walk between consecutive keyframes (sigma = rate x path step) and a weak prior on x (the
// stretch registration is the start). The normal equations are block tridiagonal: a sparse
// Cholesky solve is linear in the keyframes.
constexpr double kPriorSigma = 3.0;        // m, on the refinement's offsets
constexpr double kPriorYawSigma = 0.05;    // rad
constexpr double kMinStepSigma = 0.01;     // m, floor of the random walk per keyframe step
constexpr double kMinStepYawSigma = 1e-4;  // rad

struct KeyframeCloud {
  fusion::Cloud cloud;  ///< the keyframe's element points (ENU), labels, covariances
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
};

// The refinement's points: ground markings only. Poles, signs and lights are what moves in a
// map update; with landmarks 30 m apart a moved one would drag its keyframes along the road
// (the stretches, with many landmarks each, are robust to a moved one; one keyframe is not).
fusion::Cloud groundMarkings(const fusion::Cloud& c) {
  fusion::Cloud out;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const int l = c.labels[i];
    if (l == int(CrowdClass::kPole) || l == int(CrowdClass::kTrafficSign) ||
        l == int(CrowdClass::kTrafficLight))
      continue;
    out.points.push_back(c.points[i]);
    out.covariances.push_back(c.covariances[i]);
    out.labels.push_back(l);
  }
  return out;
}

void refineKeyframes(const fusion::Cloud& map_cloud, Lsm& lsm, const RegistrationSettings& s) {
  const int K = int(lsm.keyframes.size());
  if (K == 0 || s.refine_iterations == 0) return;
  std::vector<KeyframeCloud> kc(static_cast<std::size_t>(K));
  fusion::Cloud all;  // the drive's points only: their extent crops the map
  for (int k = 0; k < K; ++k) {
    kc[k].cloud = groundMarkings(fusion::elementCloud(lsm, k, k + 1));
    kc[k].centre = lsm.keyframes[k].T_frame_body.translation().head<2>();
    all.points.insert(all.points.end(), kc[k].cloud.points.begin(), kc[k].cloud.points.end());
  }
  if (all.size() < std::size_t(s.min_inliers)) return;
  const std::vector<double> path = pathLength(lsm);
  const double reach = *std::max_element(s.distances.begin(), s.distances.end());
  const fusion::Cloud target_cloud = cropped(map_cloud, all, reach + 1.0);
  if (target_cloud.size() < std::size_t(s.min_inliers)) return;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(3 * K);
  const Eigen::Matrix2d J = (Eigen::Matrix2d() << 0, -1, 1, 0).finished();
  for (double dist : s.distances) {
    const fusion::GicpTarget target(target_cloud, 2.0 * dist);
    for (int it = 0; it < s.refine_iterations; ++it) {
      std::vector<Eigen::Triplet<double>> trip;
      Eigen::VectorXd b = Eigen::VectorXd::Zero(3 * K);
      auto addBlock = [&](int r, int c, const Eigen::Matrix3d& m) {
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            if (m(i, j) != 0.0) trip.emplace_back(3 * r + i, 3 * c + j, m(i, j));
      };
      int inliers = 0;
      for (int k = 0; k < K; ++k) {
        const Eigen::Vector2d d = x.segment<2>(3 * k);
        const double yaw = x(3 * k + 2);
        Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
        Eigen::Vector3d g = Eigen::Vector3d::Zero();
        const fusion::Cloud& c = kc[k].cloud;
        for (std::size_t i = 0; i < c.size(); ++i) {
          const Eigen::Vector2d arm = c.points[i].head<2>() - kc[k].centre;
          Eigen::Vector3d q = c.points[i];
          q.head<2>() += d + yaw * (J * arm);
          double d2 = 0;
          const int j = target.nearest(q, c.labels[i], dist * dist, &d2);
          if (j < 0) continue;
          const Eigen::Vector2d r = q.head<2>() - target.cloud().points[j].head<2>();
          const Eigen::Matrix2d C = c.covariances[i].topLeftCorner<2, 2>() +
                                    target.cloud().covariances[j].topLeftCorner<2, 2>() +
                                    1e-4 * Eigen::Matrix2d::Identity();
          // Geman-McClure on the distance, scale half the level's: a restriped line or an
          // added marking beside a mapped one loses its pull as the level narrows, where a
          // Huber loss keeps a constant pull (a keyframe's lines split between shifted and
          // kept would meet halfway and both look re-striped).
          const double u = r.norm() / (0.5 * dist);
          const Eigen::Matrix2d W = C.inverse() / ((1 + u * u) * (1 + u * u));
          Eigen::Matrix<double, 2, 3> A;
          A << Eigen::Matrix2d::Identity(), J * arm;
          H += A.transpose() * W * A;
          g += A.transpose() * W * r;
          ++inliers;
        }
        // the weak prior on x_k
        const Eigen::Vector3d prior(1.0 / (kPriorSigma * kPriorSigma),
                                    1.0 / (kPriorSigma * kPriorSigma),
                                    1.0 / (kPriorYawSigma * kPriorYawSigma));
        H += prior.asDiagonal();
        g += prior.cwiseProduct(x.segment<3>(3 * k));
        addBlock(k, k, H);
        b.segment<3>(3 * k) -= g;
      }
      // the random walk between consecutive keyframes
      for (int k = 0; k + 1 < K; ++k) {
        const double step = path[k + 1] - path[k];
        const double st = std::max(kMinStepSigma, s.smooth_rate * step);
        const double sy = std::max(kMinStepYawSigma, s.smooth_yaw_rate * step);
        const Eigen::Vector3d w(1.0 / (st * st), 1.0 / (st * st), 1.0 / (sy * sy));
        const Eigen::Matrix3d Wm = w.asDiagonal();
        const Eigen::Vector3d r = x.segment<3>(3 * (k + 1)) - x.segment<3>(3 * k);
        addBlock(k, k, Wm);
        addBlock(k + 1, k + 1, Wm);
        addBlock(k, k + 1, -Wm);
        addBlock(k + 1, k, -Wm);
        b.segment<3>(3 * k) += Wm * r;
        b.segment<3>(3 * (k + 1)) -= Wm * r;
      }
      if (inliers < s.min_inliers) return;
      Eigen::SparseMatrix<double> H(3 * K, 3 * K);
      H.setFromTriplets(trip.begin(), trip.end());
      Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(H);
      if (solver.info() != Eigen::Success) return;
      const Eigen::VectorXd dx = solver.solve(b);
      x += dx;
      double max_step = 0;
      for (int k = 0; k < K; ++k) max_step = std::max(max_step, dx.segment<2>(3 * k).norm());
      if (max_step < kStepEps) break;
    }
  }
  for (int k = 0; k < K; ++k) {
    Pose3 D = Pose3::Identity();
    D.linear() = Eigen::AngleAxisd(x(3 * k + 2), Eigen::Vector3d::UnitZ()).toRotationMatrix();
    Eigen::Vector3d c = lsm.keyframes[k].T_frame_body.translation();
    Eigen::Vector3d t = Eigen::Vector3d::Zero();
    t.head<2>() = x.segment<2>(3 * k);
    D.translation() = c + t - D.linear() * c;
    lsm.keyframes[k].T_frame_body = D * lsm.keyframes[k].T_frame_body;
  }
}

std::vector<StretchOffset> registerDrive(const fusion::Cloud& map_cloud, int drive, Lsm& lsm,
                                         const RegistrationSettings& s) {
  const std::vector<double> path = pathLength(lsm);
  const double total = path.empty() ? 0.0 : path.back();
  const int n = std::max(1, int(std::lround(total / s.stretch_length)));
  std::vector<StretchOffset> st(n);
  std::vector<StretchCloud> clouds(n);
  const std::vector<double> vote_weights = fusion::coarseVoteWeights(kCoarse);
  std::size_t kb = 0;
  for (int j = 0; j < n; ++j) {
    StretchOffset& o = st[j];
    o.drive = drive;
    o.from = total * j / n;
    o.to = total * (j + 1) / n;
    std::size_t ke = kb;
    while (ke < path.size() && (j == n - 1 || path[ke] < o.to)) ++ke;
    if (ke > kb)
      clouds[j] =
          stretchCloud(map_cloud, fusion::elementCloud(lsm, int(kb), int(ke)), vote_weights);
    kb = ke;
  }
  // Coarse shifts: each stretch's votes with half its neighbours'; the stretch with the
  // strongest peak (most landmarks, prior coarse_prior_sigma about 0) anchors the drive, and
  // the others follow it one by one, each about its neighbour's shift (stretch_sigma: the GPS
  // error of a drive changes slowly), so that a stretch poor in landmarks cannot jump to the
  // alias one lane or one dash period away.
  std::vector<fusion::DisplacementVotes> votes(n);
  int anchor = -1;
  double best = 0;
  std::vector<Eigen::Vector2d> shift(n, Eigen::Vector2d::Zero());
  for (int j = 0; j < n; ++j) {
    if (clouds[j].cloud.size() == 0) continue;
    votes[j] = clouds[j].votes;
    for (int nb : {j - 1, j + 1})
      if (nb >= 0 && nb < n && clouds[nb].cloud.size() > 0) votes[j].add(clouds[nb].votes, 0.5);
    const fusion::DisplacementPeak p = fusion::votePeak(votes[j], kCoarse.coarse_prior_sigma);
    if (anchor < 0 || p.score > best) anchor = j, best = p.score, shift[j] = p.t;
  }
  if (anchor < 0) return st;
  for (int j = anchor + 1; j < n; ++j)
    shift[j] = votes[j].votes.empty() ? shift[j - 1]
                                      : fusion::votePeak(votes[j], s.stretch_sigma, shift[j - 1]).t;
  for (int j = anchor - 1; j >= 0; --j)
    shift[j] = votes[j].votes.empty() ? shift[j + 1]
                                      : fusion::votePeak(votes[j], s.stretch_sigma, shift[j + 1]).t;
  for (int j = 0; j < n; ++j)
    if (clouds[j].cloud.size() > 0) registerStretch(map_cloud, clouds[j], shift[j], s, st[j]);
  smooth(st);
  applyOffsets(st, path, lsm);
  if (std::any_of(st.begin(), st.end(), [](const StretchOffset& o) { return o.registered; }))
    refineKeyframes(map_cloud, lsm, s);
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
