#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "aggregate/crossing_lines.hpp"
#include "support/test_support.hpp"

using namespace mapfuse::aggregate;
using V2 = Eigen::Vector2d;

namespace {

// The definition of piecesCross (crossing_lines.hpp) by brute force: every sample of a against
// every segment of b. piecesCross skips this scan when no segment pair differs by max_angle;
// its answer must be the same on every input.
bool crossByDefinition(const std::vector<V2>& a, const std::vector<V2>& b, double near,
                       double max_angle, double step = 0.25) {
  if (a.size() < 2 || b.size() < 2) return false;
  int close = 0, crossing = 0;
  for (std::size_t k = 1; k < a.size(); ++k) {
    const V2 s = a[k] - a[k - 1];
    if (s.norm() < 1e-9) continue;
    const V2 dir = s.normalized();
    const int n = std::max(1, int(std::ceil(s.norm() / step)));
    for (int i = (k == 1 ? 0 : 1); i <= n; ++i) {
      const V2 p = a[k - 1] + s * (double(i) / n);
      bool any = false, apart = true;
      for (std::size_t j = 1; j < b.size(); ++j) {
        const V2 e = b[j] - b[j - 1];
        if (e.squaredNorm() < 1e-12) continue;
        const double t = std::clamp((p - b[j - 1]).dot(e) / e.squaredNorm(), 0.0, 1.0);
        if ((b[j - 1] + t * e - p).norm() > near) continue;
        any = true;
        if (std::abs(e.normalized().dot(dir)) >= std::cos(max_angle)) apart = false;
      }
      if (!any) continue;
      ++close;
      if (apart) ++crossing;
    }
  }
  return close > 0 && 2 * crossing > close;
}

// A piece of a lane line: `n` vertices from `start` heading `heading` (rad), turning by `turn`
// rad per segment of `seg` m, with lateral jitter of `jitter` m.
std::vector<V2> piece(std::mt19937_64& rng, V2 start, double heading, double turn, double seg,
                      int n, double jitter) {
  std::normal_distribution<double> g(0.0, jitter);
  std::vector<V2> out{start};
  for (int i = 1; i < n; ++i) {
    heading += turn;
    out.push_back(out.back() + seg * V2(std::cos(heading), std::sin(heading)) +
                  mapfuse::test::drawVector<V2>(g, rng));
  }
  return out;
}

}  // namespace

TEST_CASE("piecesCross answers as its definition on parallel, curved and crossing pieces",
          "[aggregate][lanes]") {
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double kDeg = M_PI / 180.0;
  int crossing = 0, apart = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const double heading = 2 * M_PI * u(rng);
    // half the pairs one line (small offsets), half lines meeting at 0-90 deg; straight pieces
    // of 2 vertices (most real pieces after simplification) and curved ones of up to 12
    const double cross = trial % 2 == 0 ? 0.0 : 90.0 * kDeg * u(rng);
    const int na = 2 + int(10 * u(rng) * u(rng)), nb = 2 + int(10 * u(rng) * u(rng));
    const double turn_a = (u(rng) - 0.5) * 20 * kDeg, turn_b = (u(rng) - 0.5) * 20 * kDeg;
    // every third pair far from the origin (a city's map coordinates: rounded samples)
    const V2 at = trial % 3 == 0 ? V2(2.5e5, -1.5e5) : V2(0, 0);
    // draws named in a fixed order (the last argument's first, as gcc evaluated the calls)
    const double wiggle_a = 0.01 * u(rng), step_a = 0.3 + 3 * u(rng);
    const V2 shift_a = mapfuse::test::drawVector<V2>(u, rng) * 2.0;
    const std::vector<V2> a = piece(rng, at + shift_a, heading, turn_a, step_a, na, wiggle_a);
    const double wiggle_b = 0.01 * u(rng), step_b = 0.3 + 3 * u(rng);
    const V2 shift_b = mapfuse::test::drawVector<V2>(u, rng) * 2.0;
    const std::vector<V2> b =
        piece(rng, at + shift_b - 4.0 * V2(std::cos(heading + cross), std::sin(heading + cross)),
              heading + cross, turn_b, step_b, nb, wiggle_b);
    const double max_angle = (10 + 50 * u(rng)) * kDeg;
    const bool expected = crossByDefinition(a, b, 0.4, max_angle);
    INFO("trial " << trial);
    REQUIRE(piecesCross(a, b, 0.4, max_angle) == expected);
    (expected ? crossing : apart) += 1;
  }
  // both answers occur often enough for the comparison to mean something
  CHECK(crossing >= 200);
  CHECK(apart >= 200);
}
