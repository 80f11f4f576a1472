#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "lanelet/ring_index.hpp"
#include "mapfuse/lanelet/plan.hpp"

using namespace mapfuse;
using Vec3 = Eigen::Vector3d;

TEST_CASE("the banded ring index answers as insideRingXY", "[io][lanelet2]") {
  // Lanelet-like rings (two wiggly bounds of a curved lane, 3.5 m apart) and star-shaped rings
  // with spikes, in any orientation; points around and on their vertices and edges.
  std::mt19937_64 rng(18);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int inside = 0, outside = 0;
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<Vec3> ring;
    const double heading = 2 * M_PI * u(rng), turn = (u(rng) - 0.5) * 0.05;
    const Vec3 origin(1000 * (u(rng) - 0.5), 1000 * (u(rng) - 0.5), 0);
    if (trial % 2 == 0) {  // a lanelet: left bound forward, right bound back
      const int n = 5 + int(300 * u(rng));
      std::vector<Vec3> left, right;
      double h = heading;
      Vec3 c = origin;
      for (int i = 0; i < n; ++i) {
        const Vec3 d(std::cos(h), std::sin(h), 0), nrm(-std::sin(h), std::cos(h), 0);
        left.push_back(c + (1.75 + 0.05 * (u(rng) - 0.5)) * nrm);
        right.push_back(c - (1.75 + 0.05 * (u(rng) - 0.5)) * nrm);
        c += 0.5 * d;
        h += turn;
      }
      ring = left;
      ring.insert(ring.end(), right.rbegin(), right.rend());
    } else {  // a star with spikes
      const int n = 3 + int(40 * u(rng));
      for (int i = 0; i < n; ++i) {
        const double a = heading + 2 * M_PI * i / n, r = 2 + 20 * u(rng);
        ring.push_back(origin + Vec3(r * std::cos(a), r * std::sin(a), 0));
      }
    }
    const mapfuse::lanelet::detail::RingIndex index(ring);
    Vec3 lo = ring.front(), hi = lo;
    for (const auto& p : ring) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    for (int k = 0; k < 2000; ++k) {
      Vec3 p;
      if (k % 4 == 0) {  // on a vertex or an edge (the boundary cases of the even-odd rule)
        const std::size_t i = std::size_t(u(rng) * double(ring.size())) % ring.size();
        const Vec3& b = ring[(i + 1) % ring.size()];
        p = k % 8 == 0 ? ring[i] : ring[i] + u(rng) * (b - ring[i]);
      } else {
        p = lo + Vec3(u(rng), u(rng), 0).cwiseProduct(hi - lo + Vec3(2, 2, 0)) - Vec3(1, 1, 0);
      }
      const bool expected = lanelet::insideRingXY(ring, p);
      REQUIRE(index.contains(p) == expected);
      (expected ? inside : outside) += 1;
    }
  }
  CHECK(inside > 10000);
  CHECK(outside > 10000);
}
