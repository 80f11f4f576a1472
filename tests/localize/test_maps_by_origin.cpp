// localize: the map in each drive's ENU, built once per origin (localize/maps_by_origin.hpp).
// The e2e localize tests crashed once when its cache grew while it was being iterated; here
// drives of two origins ask for their map alternately.
#include <catch2/catch.hpp>

#include "mapfuse/geo/origin.hpp"
#include "mapfuse/localize/maps_by_origin.hpp"

using namespace mapfuse;

namespace {
constexpr double kPlaceTol = 1e-6;  // m, a pole's base seen from either origin
}  // namespace

TEST_CASE("maps by origin: one map per origin, shared by the drives of that origin", "[localize]") {
  const geo::GeoOrigin a{49.0, 8.4, 110.0};
  geo::GeoOrigin b = a;
  b.lon += 0.001;  // ~73 m east of a
  VectorMap map;
  map.origin = a;
  MapInstance pole;
  pole.id = 1;
  pole.cls = CrowdClass::kPole;
  pole.points = {Eigen::Vector3d(10.0, 5.0, 0.0)};
  map.instances.push_back(pole);
  const localize::LocalizeSettings settings;
  const std::optional<VectorMap> no_truth;
  localize::MapsByOrigin maps(map, no_truth, settings);

  const int key = localize::matchKey(CrowdClass::kPole, {}, settings.match_attributes);
  const Eigen::Vector3d pole_in_b =
      geo::EnuConverter(b).toEnu(geo::EnuConverter(a).toWgs84(pole.points[0]));
  std::vector<const localize::MapIndex*> first(2, nullptr);
  for (int call = 0; call < 12; ++call) {  // a, b, a, b, ...
    const bool in_a = call % 2 == 0;
    const localize::MapInDriveFrame m = maps.at(in_a ? a : b);
    REQUIRE(m.index);
    CHECK_FALSE(m.map_to_truth);  // no truth map given
    if (!first[in_a]) first[in_a] = m.index.get();
    CHECK(m.index.get() == first[in_a]);  // built once per origin
    const Eigen::Vector3d where = in_a ? pole.points[0] : pole_in_b;
    const auto hit = m.index->nearest(key, where.head<2>(), 0.5);
    REQUIRE(hit.target);
    CHECK(hit.distance <= kPlaceTol);
  }
  CHECK(first[0] != first[1]);
  CHECK((pole_in_b - pole.points[0]).head<2>().norm() > 50.0);  // the origins differ
}
