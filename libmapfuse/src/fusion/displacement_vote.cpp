// Displacement voting (mapfuse/fusion/displacement_vote.hpp): landmarks do not repeat within the
// radius and lines one lane over have other neighbours, so aliases collect fewer votes.
#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "mapfuse/fusion/displacement_vote.hpp"
#include "mapfuse/fusion/voxel_hash.hpp"

namespace mapfuse::fusion {

DisplacementVotes voteDisplacements(const Cloud& A, const Cloud& B,
                                    const std::vector<double>& weights, double radius, double bin) {
  DisplacementVotes g;
  g.bin = bin;
  const int half = g.half = int(std::ceil(radius / bin));
  const int w = 2 * half + 1;
  std::vector<double>& hist = g.votes;
  hist.assign(std::size_t(w) * w, 0.0);
  // A's points by (cell, label), cell = radius.
  const double inv = 1.0 / radius;
  std::unordered_map<uint64_t, std::vector<int>> cells;
  auto key = [&](double x, double y, int label) {
    return packVoxelKey(int64_t(std::floor(x * inv)), int64_t(std::floor(y * inv)), label);
  };
  for (int i = 0; i < int(A.size()); ++i)
    cells[key(A.points[i].x(), A.points[i].y(), A.labels[i])].push_back(i);
  const double r2 = radius * radius;
  for (std::size_t k = 0; k < B.size(); ++k) {
    const Eigen::Vector3d& b = B.points[k];
    const int label = B.labels[k];
    const double wl = label < int(weights.size()) ? weights[label] : 1.0;
    if (wl <= 0) continue;
    const int64_t cx = int64_t(std::floor(b.x() * inv)), cy = int64_t(std::floor(b.y() * inv));
    for (int64_t dx = -1; dx <= 1; ++dx)
      for (int64_t dy = -1; dy <= 1; ++dy) {
        const auto it = cells.find(packVoxelKey(cx + dx, cy + dy, label));
        if (it == cells.end()) continue;
        for (int i : it->second) {
          const Eigen::Vector2d d = (A.points[i] - b).head<2>();
          if (d.squaredNorm() > r2) continue;
          const double fx = d.x() / bin + half, fy = d.y() / bin + half;
          const int ix = int(std::floor(fx)), iy = int(std::floor(fy));
          if (ix < 0 || iy < 0 || ix + 1 >= w || iy + 1 >= w) continue;
          const double ux = fx - ix, uy = fy - iy;
          hist[std::size_t(iy) * w + ix] += wl * (1 - ux) * (1 - uy);
          hist[std::size_t(iy) * w + ix + 1] += wl * ux * (1 - uy);
          hist[std::size_t(iy + 1) * w + ix] += wl * (1 - ux) * uy;
          hist[std::size_t(iy + 1) * w + ix + 1] += wl * ux * uy;
        }
      }
  }
  return g;
}

DisplacementPeak votePeak(const DisplacementVotes& g, double prior_sigma,
                          const Eigen::Vector2d& prior_centre) {
  DisplacementPeak res;
  const int half = g.half, w = 2 * half + 1;
  const double bin = g.bin;
  const std::vector<double>& hist = g.votes;
  // [1 2 1]^2 smoothing and the Gaussian prior.
  std::vector<double> sm(hist.size(), 0.0);
  const double k3[3] = {0.25, 0.5, 0.25};
  for (int y = 1; y + 1 < w; ++y)
    for (int x = 1; x + 1 < w; ++x) {
      double v = 0;
      for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i)
          v += k3[j + 1] * k3[i + 1] * hist[std::size_t(y + j) * w + x + i];
      const double dx = (x - half) * bin - prior_centre.x(),
                   dy = (y - half) * bin - prior_centre.y();
      sm[std::size_t(y) * w + x] =
          v * std::exp(-0.5 * (dx * dx + dy * dy) / (prior_sigma * prior_sigma));
    }
  int best = 0;
  for (int i = 1; i < int(sm.size()); ++i)
    if (sm[i] > sm[best]) best = i;
  const int bx = best % w, by = best / w;
  res.score = sm[best];
  // Sub-bin peak by a parabola through the neighbours.
  auto at = [&](int x, int y) { return sm[std::size_t(y) * w + x]; };
  double ox = 0, oy = 0;
  if (bx > 0 && bx + 1 < w) {
    const double l = at(bx - 1, by), c = at(bx, by), r = at(bx + 1, by), den = l - 2 * c + r;
    if (den < 0) ox = std::clamp(0.5 * (l - r) / den, -0.5, 0.5);
  }
  if (by > 0 && by + 1 < w) {
    const double l = at(bx, by - 1), c = at(bx, by), r = at(bx, by + 1), den = l - 2 * c + r;
    if (den < 0) oy = std::clamp(0.5 * (l - r) / den, -0.5, 0.5);
  }
  res.t = Eigen::Vector2d((bx - half + ox) * bin, (by - half + oy) * bin);
  return res;
}

}  // namespace mapfuse::fusion
