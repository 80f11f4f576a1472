#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>

#include "mapfuse/core/error.hpp"
#include "mapfuse/geo/origin.hpp"
#include "mapfuse/geo/oxts.hpp"
#include "mapfuse/io/oxts_line.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;

namespace {
constexpr double kMm = 1e-3;        // ENU round-trip tolerance, m
constexpr double kDegPerMm = 1e-8;  // lat/lon tolerance, deg (~1 mm)
}  // namespace

namespace {
// Independent reference: WGS84 geodetic -> ECEF -> ENU with the textbook closed forms
// (a = 6378137 m, f = 1/298.257223563), no GeographicLib involved.
Eigen::Vector3d ecef(double lat_deg, double lon_deg, double h) {
  const double a = 6378137.0, f = 1.0 / 298.257223563, e2 = f * (2 - f);
  const double lat = lat_deg * M_PI / 180, lon = lon_deg * M_PI / 180;
  const double N = a / std::sqrt(1 - e2 * std::sin(lat) * std::sin(lat));
  return {(N + h) * std::cos(lat) * std::cos(lon), (N + h) * std::cos(lat) * std::sin(lon),
          (N * (1 - e2) + h) * std::sin(lat)};
}
Eigen::Matrix3d R_enu_ecef(const geo::LatLonAlt& o) {
  const double lat = o.lat * M_PI / 180, lon = o.lon * M_PI / 180;
  Eigen::Matrix3d R;
  R << -std::sin(lon), std::cos(lon), 0, -std::sin(lat) * std::cos(lon),
      -std::sin(lat) * std::sin(lon), std::cos(lat), std::cos(lat) * std::cos(lon),
      std::cos(lat) * std::sin(lon), std::sin(lat);
  return R;
}
Eigen::Vector3d referenceEnu(const geo::LatLonAlt& o, const geo::LatLonAlt& p) {
  return R_enu_ecef(o) * (ecef(p.lat, p.lon, p.alt) - ecef(o.lat, o.lon, o.alt));
}
}  // namespace

TEST_CASE("ENU <-> WGS84 matches an independent ECEF reference", "[geo]") {
  const geo::LatLonAlt origin{49.0, 8.0, 100.0};
  const geo::EnuConverter enu(origin);
  for (const geo::LatLonAlt q :
       {geo::LatLonAlt{49.001, 8.002, 110.0}, geo::LatLonAlt{48.95, 8.07, 80.0},
        geo::LatLonAlt{49.05, 7.93, 130.0}}) {
    const Eigen::Vector3d p = enu.toEnu(q);
    CHECK((p - referenceEnu(origin, q)).norm() < kMm);
    const geo::LatLonAlt back = enu.toWgs84(p);
    CHECK(back.lat == Approx(q.lat).margin(kDegPerMm));
    CHECK(back.lon == Approx(q.lon).margin(kDegPerMm));
    CHECK(back.alt == Approx(q.alt).margin(kMm));
  }
}

TEST_CASE("ENU round trip over 10 km stays within a millimetre", "[geo]") {
  const geo::EnuConverter enu({49.011212804408, 8.4228850417969, 112.83492279053});
  for (const Eigen::Vector3d& p :
       {Eigen::Vector3d(10000, -5000, 30), Eigen::Vector3d(-7000, 9000, -20)}) {
    CHECK((enu.toEnu(enu.toWgs84(p)) - p).norm() < kMm);
  }
}

TEST_CASE("a pose re-expressed about another origin turns with the ENU frames", "[geo]") {
  constexpr double kRotationTolerance = 1e-8;                       // rad
  const geo::LatLonAlt a{49.0, 8.0, 100.0}, b{49.03, 8.05, 120.0};  // ~5 km apart
  const geo::EnuConverter from(a), to(b);
  Eigen::Isometry3d T_a_body = Eigen::Isometry3d::Identity();
  T_a_body.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T_a_body.translation() = Eigen::Vector3d(120.0, -40.0, 2.0);
  const Eigen::Isometry3d T_b_body = geo::reexpressPose(T_a_body, from, to);
  // Independent reference: the rotation between the two ENU frames through ECEF.
  const Eigen::Matrix3d R_b_a = R_enu_ecef(b) * R_enu_ecef(a).transpose();
  const Eigen::Matrix3d expected = R_b_a * T_a_body.linear();
  CHECK(Eigen::AngleAxisd(expected.transpose() * T_b_body.linear()).angle() < kRotationTolerance);
  CHECK(Eigen::AngleAxisd(R_b_a).angle() > 1e-4);  // the frames do differ: a real check
  // A point 30 m ahead of the body lands on the same WGS84 point either way.
  const Eigen::Vector3d ahead(30.0, 0.0, 0.0);
  CHECK((to.toEnu(from.toWgs84(T_a_body * ahead)) - T_b_body * ahead).norm() < kMm);
}

TEST_CASE("an invalid origin is refused", "[geo]") {
  CHECK_THROWS_AS(geo::EnuConverter({95.0, 8.0, 0.0}), InputError);
  CHECK_THROWS_AS(geo::EnuConverter({std::nan(""), 8.0, 0.0}), InputError);
}

TEST_CASE("KITTI drive 0005 frame 0 OXTS is read and converted with the devkit convention",
          "[geo][shared]") {
  const auto file = test::requireShared(
      "data/kitti_raw/2011_09_26/2011_09_26_drive_0005_sync/oxts/data/0000000000.txt");
  const std::string line = test::readText(file);
  const geo::OxtsRecord r = io::parseOxtsLine(line, file.string());
  CHECK(r.lat == 49.011212804408);
  CHECK(r.lon == 8.4228850417969);
  CHECK(r.alt == 112.83492279053);
  CHECK(r.numsats == 10);

  // Devkit: scale = cos(lat0); tx = s*lon*pi*R/180; ty = s*R*ln(tan((90+lat)*pi/360)).
  const double s = std::cos(49.011212804408 * M_PI / 180.0);
  const double tx = s * 8.4228850417969 * M_PI * 6378137.0 / 180.0;
  const double ty = s * 6378137.0 * std::log(std::tan((90.0 + 49.011212804408) * M_PI / 360.0));
  const Pose3 T = geo::oxtsToMercatorPose(r, geo::mercatorScale(r.lat));
  CHECK(T.translation().x() == Approx(tx).epsilon(1e-12));
  CHECK(T.translation().y() == Approx(ty).epsilon(1e-12));
  CHECK(T.translation().z() == Approx(112.83492279053));
  const Eigen::Vector3d rpy = rpyFromRotation(T.linear());
  CHECK(rpy.z() == Approx(r.yaw).margin(1e-12));
  CHECK(rpy.x() == Approx(r.roll).margin(1e-12));

  // ENU option: the first frame is the origin of its own ENU frame.
  const geo::EnuConverter enu({r.lat, r.lon, r.alt});
  CHECK(geo::oxtsToEnuPose(r, enu).translation().norm() < kMm);
}

TEST_CASE("malformed OXTS lines name the field", "[geo]") {
  try {
    io::parseOxtsLine("49.0 8.0 abc", "x.txt");
    FAIL("no exception");
  } catch (const ParseError& e) {
    CHECK(e.file() == "x.txt");
    CHECK(e.field() == "alt");
  }
  try {
    io::parseOxtsLine("49.0 8.0 1.0", "y.txt");
    FAIL("no exception");
  } catch (const ParseError& e) {
    CHECK(e.field() == "roll");
    CHECK(e.exitCode() == ExitCode::kBadInput);
  }
}
