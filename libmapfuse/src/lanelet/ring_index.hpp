#pragma once
/// @file Point-in-ring tests against one ring many times (drive samples against a lanelet):
/// the ring's edges bucketed by horizontal bands, so a test reads only the edges of the band
/// its point lies in. The answer is insideRingXY's, bit for bit: the even-odd rule toggles only
/// on edges whose y-range holds p.y, all of which lie in p.y's band, by the same expression.
#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <vector>

namespace mapfuse::lanelet::detail {

class RingIndex {
 public:
  /// @param band m, height of a band (a long edge is listed in every band it spans)
  explicit RingIndex(const std::vector<Eigen::Vector3d>& ring, double band = 0.5)
      : ring_(&ring), band_(band) {
    if (ring.empty()) return;
    double lo = ring.front().y(), hi = lo;
    for (const auto& p : ring) lo = std::min(lo, p.y()), hi = std::max(hi, p.y());
    band_ = std::max(band_, (hi - lo) / double(kMaxBands));  // bounded memory on any ring
    first_ = int64_t(std::floor(lo / band_));
    edges_.resize(std::size_t(int64_t(std::floor(hi / band_)) - first_ + 1));
    for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
      const double y0 = std::min(ring[i].y(), ring[j].y()), y1 = std::max(ring[i].y(), ring[j].y());
      for (int64_t b = int64_t(std::floor(y0 / band_)); b <= int64_t(std::floor(y1 / band_)); ++b)
        edges_[std::size_t(b - first_)].push_back({uint32_t(i), uint32_t(j)});
    }
  }

  /// @brief insideRingXY(ring, p).
  bool contains(const Eigen::Vector3d& p) const {
    const double f = std::floor(p.y() / band_);
    if (!(f >= double(first_) && f < double(first_) + double(edges_.size()))) return false;
    const auto& ring = *ring_;
    bool inside = false;
    for (const auto& [i, j] : edges_[std::size_t(int64_t(f) - first_)]) {
      const Eigen::Vector3d& a = ring[i];
      const Eigen::Vector3d& b = ring[j];
      if ((a.y() > p.y()) != (b.y() > p.y()) &&
          p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
        inside = !inside;
    }
    return inside;
  }

 private:
  static constexpr int64_t kMaxBands = 100000;
  struct Edge {
    uint32_t i, j;
  };
  const std::vector<Eigen::Vector3d>* ring_;
  double band_;
  int64_t first_ = 0;
  std::vector<std::vector<Edge>> edges_;
};

}  // namespace mapfuse::lanelet::detail
