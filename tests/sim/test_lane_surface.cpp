// The road surface of map worlds (sim/lane_surface.hpp): a simulated vehicle rolls with the
// superelevation the OpenDRIVE file states (an independent oracle: the file's own records).
#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>

#include "mapfuse/geo/origin.hpp"
#include "mapfuse/sim/drive.hpp"
#include "mapfuse/sim/map_world.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;

namespace {
constexpr const char* kBanked =
    "data/maps/opendrive-esmini/xodr__straight_500_superelevation_elevation.xodr";
// The file's superelevation (road 1, straight along x from 0 to 500 m): 0 to s = 50 m, a cubic
// rise to 0.5 rad at 150 m, a cubic fall to 0 at 250 m, then 0.
double fileSuperelevation(double s) {
  if (s < 50.0) return 0.0;
  if (s < 150.0) return 0.00015 * std::pow(s - 50.0, 2) - 1.0e-6 * std::pow(s - 50.0, 3);
  if (s < 250.0) return 0.5 - 0.00015 * std::pow(s - 150.0, 2) + 1.0e-6 * std::pow(s - 150.0, 3);
  return 0.0;
}
// rad: the body's own roll oscillation (DriveParams default 0.005) plus the plane fitted over
// ±6 m of a cross-section that turns by up to 0.0075 rad/m
constexpr double kRollTol = 0.02;
}  // namespace

TEST_CASE("map worlds: the body rolls with the file's superelevation (28 deg at its peak)") {
  const auto path = test::requireShared(kBanked);
  geo::GeoOrigin origin{49.0, 8.4, 110.0};
  const sim::World world = sim::loadMapWorld(path.string(), true, {}, &origin);
  REQUIRE(world.surface_height);
  const auto routes = sim::planRoutes(world, 1, 450.0, 3);
  REQUIRE(routes.size() == 1);
  INFO("route from " << routes[0].front().transpose() << " to " << routes[0].back().transpose());
  const geo::EnuConverter enu(origin);
  const sim::Drive d =
      sim::simulateDrive(routes[0], sim::DriveParams{}, enu, 5, world.surface_height);
  double worst = 0.0, peak = 0.0;
  int n = 0;
  for (std::size_t k = 0; k < d.truth.size(); k += 20) {
    const Eigen::Vector3d x_axis = d.truth[k].linear().col(0), y_axis = d.truth[k].linear().col(1);
    const double s = d.truth[k].translation().x();
    if (s < 5.0 || s > 495.0) continue;
    // driving along +x the body's left is the road's +t side (z = e + t sin(roll))
    const double expected = (x_axis.x() > 0 ? 1.0 : -1.0) * fileSuperelevation(s);
    worst = std::max(worst, std::abs(std::asin(y_axis.z()) - expected));
    peak = std::max(peak, std::abs(expected));
    ++n;
  }
  INFO(n << " samples, largest superelevation " << peak << " rad, worst roll error " << worst
         << " rad");
  REQUIRE(n > 50);
  CHECK(peak > 0.45);
  CHECK(worst < kRollTol);
}
