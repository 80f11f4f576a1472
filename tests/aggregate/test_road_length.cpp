// coveredRoadKm against a brute-force reading of its definition (road_length.hpp): keyframe
// steps sampled every metre, a sample counting when no sample of an earlier drive lies within
// the tolerance. The function answers most samples from a grid of occupied cells; the answer
// must be the one the search over every earlier sample gives.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "mapfuse/aggregate/road_length.hpp"

using namespace mapfuse;
using namespace mapfuse::aggregate;

namespace {

// The definition, O(samples^2): the same 1 m sampling, every earlier drive's sample compared.
double referenceRoadKm(const std::vector<Lsm>& lsms, double tolerance) {
  std::vector<Eigen::Vector3d> earlier;
  double metres = 0;
  for (const Lsm& lsm : lsms) {
    std::vector<Eigen::Vector3d> samples;
    for (std::size_t i = 1; i < lsm.keyframes.size(); ++i) {
      const Eigen::Vector3d a = lsm.keyframes[i - 1].T_frame_body.translation();
      const Eigen::Vector3d b = lsm.keyframes[i].T_frame_body.translation();
      const int n = std::max(1, int(std::ceil((b - a).norm())));
      for (int k = 0; k < n; ++k) {
        const Eigen::Vector3d s = a + (b - a) * (double(k) + 0.5) / n;
        bool known = false;
        for (const auto& e : earlier) known = known || (e - s).head<2>().norm() <= tolerance;
        if (!known) metres += (b - a).norm() / n;
        samples.push_back(s);
      }
    }
    earlier.insert(earlier.end(), samples.begin(), samples.end());
  }
  return metres / 1000.0;
}

}  // namespace

TEST_CASE("covered road km equals the brute-force count over every earlier sample",
          "[aggregate][road_length]") {
  // 12 drives along one wiggly road at lateral offsets 0-18 m (some within the tolerance of
  // the first, some beyond it), each with its own branch: samples near cell corners, on both
  // sides of the tolerance.
  std::mt19937 rng(18);
  std::uniform_real_distribution<double> offset(0.0, 18.0), step(2.0, 9.0), turn(-0.3, 0.3);
  std::vector<Lsm> lsms(12);
  for (std::size_t d = 0; d < lsms.size(); ++d) {
    const double lateral = d == 0 ? 0.0 : offset(rng);
    double x = 0, heading = 0;
    for (int k = 0; k < 60; ++k) {
      Keyframe kf;
      kf.id = k;
      kf.stamp = k;
      const double y = lateral + 20.0 * std::sin(x / 60.0) + (k > 45 ? 4.0 * (k - 45) * d : 0.0);
      kf.T_frame_body.translation() = Eigen::Vector3d(x, y, 0);
      lsms[d].keyframes.push_back(kf);
      heading += turn(rng);
      x += step(rng) * (1.0 + 0.1 * std::cos(heading));
    }
  }
  for (double tolerance : {10.0, 3.0, 0.7}) {
    RoadLengthSettings s;
    s.tolerance = tolerance;
    const double reference = referenceRoadKm(lsms, tolerance);
    CAPTURE(tolerance, reference);
    CHECK(reference > 0.4);  // the branches and the farther offsets add road
    CHECK(coveredRoadKm(lsms, s) == Approx(reference).epsilon(1e-12));
  }
}
