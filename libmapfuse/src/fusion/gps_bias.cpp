// Eq. (9) GPS priors with a slowly varying bias per traversal (gps_bias.hpp).
#include "gps_bias.hpp"

#include <algorithm>
#include <cmath>

#include "graph_covariances.hpp"

namespace mapfuse::fusion::detail {

namespace {

constexpr double kNodeRotationSigma = 1e-4;  // rad: a bias node's rotation is held (identity)

/// Square-root information of a diagonal with these sigmas (0: no information on that row).
Matrix6d diagonalSqrtInformation(const Vector6d& sigma) {
  Matrix6d L = Matrix6d::Zero();
  for (int i = 0; i < 6; ++i) L(i, i) = sigma[i] > 0 ? 1.0 / sigma[i] : 0.0;
  return L;
}

/// Median over the keyframes of the position sigma along `axis` (georef's covariance).
double medianSigma(const std::vector<Keyframe>& kfs, int axis) {
  std::vector<double> v;
  for (const auto& k : kfs) v.push_back(std::sqrt(std::max(0.0, k.covariance(axis, axis))));
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return std::max(v[v.size() / 2], 1e-3);
}

Pose3 translationOnly(const Eigen::Vector3d& t) {
  Pose3 T = Pose3::Identity();
  T.translation() = t;
  return T;
}

}  // namespace

GpsPriorTerms gpsPriorTerms(const std::vector<Lsm>& priors, const AlignSettings& s) {
  GpsPriorTerms g;
  const int n = int(priors.size());
  g.nodes.resize(n);
  g.node_keyframe.resize(n);
  if (s.gps_bias_sigma <= 0) {  // eq. (9) as printed: one independent prior per keyframe
    for (int l = 0; l < n; ++l)
      for (int k = 0; k < int(priors[l].keyframes.size()); ++k) {
        const Keyframe& kf = priors[l].keyframes[k];
        g.anchors.push_back({l, k, kf.T_frame_body, sqrtInformation(priorCovariance(kf, s))});
      }
    return g;
  }
  Vector6d held;  // the rotation of a node; its translation free
  held << 0, 0, 0, kNodeRotationSigma, kNodeRotationSigma, kNodeRotationSigma;
  for (int l = 0; l < n; ++l) {
    const auto& kfs = priors[l].keyframes;
    if (kfs.empty()) continue;
    const double t0 = kfs.front().stamp, span = std::max(0.0, kfs.back().stamp - t0);
    const int steps = std::max(0, int(std::ceil(span / s.gps_bias_interval - 1e-9)));
    const double dt = steps > 0 ? span / steps : 0.0;
    // Nodes at t0 + j dt, each anchored at the keyframe nearest in time.
    std::size_t k = 0;
    for (int j = 0; j <= steps; ++j) {
      const double t = t0 + j * dt;
      while (k + 1 < kfs.size() && std::abs(kfs[k + 1].stamp - t) <= std::abs(kfs[k].stamp - t))
        ++k;
      g.node_keyframe[l].push_back(int(k));
      g.nodes[l].push_back(translationOnly(kfs[k].T_frame_body.translation()));
    }
    const int chain = n + l;
    // The first node: the bias is zero-mean with gps_bias_sigma, but never looser than the
    // drive's own GPS claims (its median keyframe sigma: an RTK drive's bias stays within its
    // centimetres, and a wrong registration cannot carry the whole drive away); every node's
    // rotation held.
    const double sh = std::min(s.gps_bias_sigma, medianSigma(kfs, 0));
    const double sv = std::min(s.gps_bias_vertical_sigma, medianSigma(kfs, 2));
    Vector6d first;
    first << sh, sh, sv, kNodeRotationSigma, kNodeRotationSigma, kNodeRotationSigma;
    for (int j = 0; j <= steps; ++j)
      g.anchors.push_back(
          {chain, j, g.nodes[l][j], diagonalSqrtInformation(j == 0 ? first : held)});
    // Random walk between consecutive nodes: the anchors' difference, gps_bias_walk sqrt(dt).
    const double sw = s.gps_bias_walk * std::sqrt(dt);
    Vector6d walk;
    walk << sw, sw, sw, 0, 0, 0;
    for (int j = 0; j < steps; ++j)
      g.terms.push_back({chain, j, chain, j + 1,
                         g.nodes[l][j].inverse() * g.nodes[l][j + 1],
                         diagonalSqrtInformation(walk)});
    // Keyframe k seen from the node nearest in time (the bias piecewise constant over
    // gps_bias_interval: between neighbours it differs by gps_bias_walk sqrt(dt), 0.16 m at
    // the defaults, against georef's metres of keyframe sigma).
    for (int kk = 0; kk < int(kfs.size()); ++kk) {
      const double f = dt > 0 ? std::clamp((kfs[kk].stamp - t0) / dt, 0.0, double(steps)) : 0.0;
      const int j = int(std::lround(f));
      g.terms.push_back({chain, j, l, kk, g.nodes[l][j].inverse() * kfs[kk].T_frame_body,
                         sqrtInformation(priorCovariance(kfs[kk], s))});
    }
  }
  return g;
}

std::vector<Pose3> gpsBiasNodeStart(const GpsPriorTerms& g, const std::vector<Lsm>& lsms,
                                    const std::vector<Lsm>& priors) {
  std::vector<Pose3> out;
  for (std::size_t l = 0; l < g.nodes.size(); ++l)
    for (std::size_t j = 0; j < g.nodes[l].size(); ++j) {
      const int k = g.node_keyframe[l][j];
      Pose3 T = g.nodes[l][j];
      T.translation() += lsms[l].keyframes[k].T_frame_body.translation() -
                         priors[l].keyframes[k].T_frame_body.translation();
      out.push_back(T);
    }
  return out;
}

}  // namespace mapfuse::fusion::detail
