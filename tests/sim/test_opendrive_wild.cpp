// OpenDRIVE as found in the wild (issues 35, 37; docs/formats.md "Map content checks"): the
// reading policy (clamp and warn once per kind, drop what cannot be placed, refuse structural
// nonsense), spherical and other georeferences against Snyder's closed form, road-mark objects
// as ground arrows, maps without georeference in a local frame, and the esmini corpus.
#include <GeographicLib/TransverseMercator.hpp>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>

#include "mapfuse/core/error.hpp"
#include "mapfuse/geo/map_projection.hpp"
#include "mapfuse/io/opendrive.hpp"
#include "mapfuse/sim/map_world.hpp"
#include "mapfuse/sim/opendrive_world.hpp"
#include "sim/opendrive_geometry.hpp"
#include "support/test_support.hpp"

using namespace mapfuse;
using Catch::Contains;
namespace fs = std::filesystem;

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kMm = 1e-3;  // m: positions from closed forms

/// One straight road "R" along x (length 100 m, two 3.5 m lanes, a solid centre line);
/// `geometry` replaces its plan view, `extra_road` is appended inside <road>, `more` after it.
std::string roadMap(const std::string& header = "", const std::string& geometry = "",
                    const std::string& extra_road = "", const std::string& more = "",
                    const std::string& centre_mark = R"(<roadMark sOffset="0" type="solid"/>)",
                    const std::string& length = "100") {
  const std::string pv =
      geometry.empty() ? R"(<geometry s="0" x="0" y="0" hdg="0" length="100"><line/></geometry>)"
                       : geometry;
  return R"(<?xml version="1.0"?><OpenDRIVE><header>)" + header + R"(</header>
  <road id="R" length=")" +
         length + R"(" junction="-1"><planView>)" + pv + R"(</planView>
    <lanes><laneSection s="0">
      <left><lane id="1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></left>
      <center><lane id="0" type="none">)" +
         centre_mark + R"(</lane></center>
      <right><lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></right>
    </laneSection></lanes>)" +
         extra_road + R"(</road>)" + more + R"(</OpenDRIVE>)";
}

sim::World worldOf(const std::string& xml) {
  const io::OdrMap map = io::parseOpenDrive(xml, "wild.xodr");
  return sim::worldFromOpenDrive(map, sim::openDriveOrigin(map, geo::GeoOrigin{48.0, 11.0, 0.0}));
}

std::string messageOf(const std::string& xml) {
  try {
    worldOf(xml);
  } catch (const Error& e) {
    return e.what();
  }
  return "(accepted)";
}

double lineLength(const sim::World& w, CrowdClass cls) {
  double len = 0.0;
  for (const auto& m : w.truth.instances)
    if (m.cls == cls)
      for (std::size_t i = 1; i < m.points.size(); ++i)
        len += (m.points[i] - m.points[i - 1]).norm();
  return len;
}

int countOf(const sim::World& w, CrowdClass cls) {
  int n = 0;
  for (const auto& m : w.truth.instances) n += m.cls == cls;
  return n;
}
}  // namespace

TEST_CASE("OpenDRIVE wild: a negative road-mark sOffset is clamped with one warning",
          "[sim][opendrive][wild]") {
  // A survey map's road marks start at sOffset -4.575 (80 records on 11 roads).
  const std::string marks = R"(<roadMark sOffset="-4.575" type="solid"/>)"
                            R"(<roadMark sOffset="-1.0" type="solid"/>)";
  const sim::World w = worldOf(roadMap("", "", "", "", marks));
  const InputWarnings::Entry& e =
      w.warnings.entries().at("roadMark@sOffset negative (clamped to 0)");
  CHECK(e.count == 2);
  CHECK_THAT(e.first, Contains("wild.xodr") && Contains("road R") && Contains("-4.575"));
  // Both records start at the section start: the second (from 0 too) covers the road.
  CHECK(lineLength(w, CrowdClass::kLaneLine) == Approx(100.0).margin(kMm));
}

TEST_CASE("OpenDRIVE wild: spherical and other georeferences", "[sim][opendrive][wild][geo]") {
  // The survey map's georeference: a transverse Mercator on a sphere of radius a.
  const std::string survey =
      "+proj=tmerc +a=6378137 +b=6378137 +lon_0=11.5 +x_0=-0 +y_0=-5453802.49 +k=1.0 "
      "+units=m +nadgrids=@null +wktext +no_defs";
  const auto proj = geo::MapProjection::fromProj(survey, "survey.xodr");
  // Snyder (1987) eq. 8-1, 8-3, spherical transverse Mercator: x = R k0 atanh(B),
  // y = R k0 (atan(tan(phi) / cos(dlon)) - phi0), B = cos(phi) sin(dlon).
  const double R = 6378137.0, rad = kPi / 180.0;
  for (const auto& [lat, lon] : {std::pair{49.2, 11.5}, {49.25, 11.6}, {48.9, 11.2}}) {
    const double dl = (lon - 11.5) * rad, phi = lat * rad;
    const double x = R * std::atanh(std::cos(phi) * std::sin(dl));
    const double y = R * std::atan2(std::tan(phi), std::cos(dl)) - 5453802.49;
    const Eigen::Vector2d m = proj.fromWgs84(lat, lon);
    CHECK(std::hypot(m.x() - x, m.y() - y) < kMm);
    const geo::LatLonAlt back = proj.toWgs84(x, y, 0.0);
    CHECK(std::abs(back.lat - lat) < 1e-10);
    CHECK(std::abs(back.lon - lon) < 1e-10);
  }
  // +R, +ellps=sphere and +a with +rf describe the same figures as their named equivalents.
  const auto wgs = geo::MapProjection::fromProj("+proj=tmerc +lon_0=9 +ellps=WGS84");
  const auto arf =
      geo::MapProjection::fromProj("+proj=tmerc +lon_0=9 +a=6378137 +rf=298.257223563");
  CHECK((wgs.fromWgs84(50, 9.3) - arf.fromWgs84(50, 9.3)).norm() < kMm);
  const auto r = geo::MapProjection::fromProj("+proj=tmerc +lon_0=9 +R=6370997");
  const auto sphere = geo::MapProjection::fromProj("+proj=tmerc +lon_0=9 +ellps=sphere");
  CHECK((r.fromWgs84(50, 9.3) - sphere.fromWgs84(50, 9.3)).norm() < kMm);
  // What cannot be represented is refused naming the file and the parameter; k is bounded.
  auto message = [](const std::string& p) {
    try {
      geo::MapProjection::fromProj(p, "m.xodr");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  CHECK_THAT(message("+proj=tmerc +datum=WGS84 +k=1e300"),
             Contains("m.xodr: georeference") && Contains("+k=1e300 is outside [0.1, 10]"));
  CHECK_THAT(message("+proj=tmerc +datum=WGS84 +k=1e-300"), Contains("+k=1e-300 is outside"));
  CHECK_THAT(message("+proj=tmerc +a=6378137 +nadgrids=BETA2007.gsb"),
             Contains("m.xodr") && Contains("+nadgrids=BETA2007.gsb"));
  CHECK_THAT(message("+proj=tmerc +datum=NAD27"), Contains("datum 'NAD27'"));
  CHECK_THAT(message("+proj=tmerc +a=1"), Contains("+a=1 is outside"));
  CHECK_THAT(message("+proj=tmerc +ellps=WGS84 +pm=paris"), Contains("parameter +pm"));
  // Through the map: the error names the .xodr file.
  CHECK_THAT(messageOf(roadMap("<geoReference><![CDATA[+proj=tmerc +k=1e300]]></geoReference>")),
             Contains("wild.xodr: georeference") && Contains("+k=1e300"));
  // The survey map's georeference places the map: (0, 0) is its origin, lon_0 = 11.5.
  const io::OdrMap m = io::parseOpenDrive(
      roadMap("<geoReference><![CDATA[" + survey + "]]></geoReference>"), "wild.xodr");
  const geo::GeoOrigin o = sim::openDriveOrigin(m, geo::GeoOrigin{});
  const geo::LatLonAlt expect = proj.toWgs84(0, 0, 0);
  CHECK(o.lat == Approx(expect.lat).margin(1e-12));
  CHECK(o.lon == Approx(11.5).margin(1e-9));
  // On the central meridian of the sphere y = R phi: y_0 = -5453802.49 puts map (0, 0) there.
  CHECK(o.lat == Approx(5453802.49 / R / rad).margin(1e-9));
}

TEST_CASE("OpenDRIVE wild: road-mark objects become ground arrows", "[sim][opendrive][wild]") {
  const std::string objects = R"(<objects>
      <object id="a1" type="roadMark" subtype="arrowStraight" name="arrow" s="50" t="-1.75"
              zOffset="0" hdg="0" length="5" width="1.2"/>
      <object id="a2" type="roadMark" name="text" s="20" t="1.75" hdg="0">
        <outline><cornerLocal u="0" v="0" z="0"/><cornerLocal u="2" v="0" z="0"/>
                 <cornerLocal u="2" v="1" z="0"/></outline></object>
      <object id="b" type="roadMark" s="10" t="0"/>
    </objects>)";
  const sim::World w = worldOf(roadMap("", "", objects));
  REQUIRE(countOf(w, CrowdClass::kGroundArrow) == 2);
  CHECK(w.stats.at("arrows") == 2);
  CHECK(w.stats.at("objects_skipped") == 1);  // no outline and no size: nothing to draw
  for (const auto& m : w.truth.instances) {
    if (m.cls != CrowdClass::kGroundArrow) continue;
    // The shoelace area: 5 x 1.2 m rectangle centred at (50, -1.75); the triangle 1 m^2.
    double area = 0.0;
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < m.points.size(); ++i) {
      const auto& p = m.points[i];
      const auto& q = m.points[(i + 1) % m.points.size()];
      area += 0.5 * (p.x() * q.y() - q.x() * p.y());
      c += p / double(m.points.size());
    }
    if (m.points.size() == 4) {
      CHECK(std::abs(area) == Approx(6.0).margin(1e-3));
      CHECK((c - Eigen::Vector3d(50, -1.75, 0)).norm() < kMm);
      CHECK(m.note.empty());
    } else {
      CHECK(std::abs(area) == Approx(1.0).margin(1e-3));
      CHECK_THAT(m.note, Contains("road-mark object 'text'"));
    }
  }
}

TEST_CASE("OpenDRIVE wild: content checks repair, drop or refuse per the table",
          "[sim][opendrive][wild][bad]") {
  auto kinds = [](const sim::World& w) {
    std::string all;
    for (const auto& [k, e] : w.warnings.entries()) all += k + " | " + e.first + "\n";
    return all;
  };
  SECTION("a 5.5 km plan-view gap drops the road, not driven as road") {
    const std::string gap =
        R"(<geometry s="0" x="0" y="0" hdg="0" length="50"><line/></geometry>)"
        R"(<geometry s="50" x="5550" y="0" hdg="0" length="50"><line/></geometry>)";
    const std::string other = R"(<road id="S" length="100" junction="-1"><planView>
      <geometry s="0" x="0" y="20" hdg="0" length="100"><line/></geometry></planView>
      <lanes><laneSection s="0"><center><lane id="0" type="none">
      <roadMark sOffset="0" type="solid"/></lane></center><right><lane id="-1" type="driving">
      <width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></right></laneSection></lanes></road>)";
    const sim::World w = worldOf(roadMap("", gap, "", other));
    CHECK_THAT(kinds(w), Contains("gap > 1 m (road dropped)") && Contains("5500 m gap"));
    CHECK(w.stats.at("roads") == 1);
    CHECK(w.laneLength() == Approx(100.0).margin(0.01));  // road S's one lane only
    CHECK_THAT(messageOf(roadMap("", gap)), Contains("no road is left"));
  }
  SECTION("a road length that disagrees with its plan view takes the plan view's") {
    const sim::World w =
        worldOf(roadMap("", "", "", "", R"(<roadMark sOffset="0" type="solid"/>)", "2000"));
    CHECK_THAT(kinds(w), Contains("road length differs") && Contains("length=2000"));
    CHECK(lineLength(w, CrowdClass::kLaneLine) == Approx(100.0).margin(kMm));
  }
  SECTION("links to missing roads and junctions are dropped with a warning") {
    const sim::World w = worldOf(roadMap(
        "", "",
        R"(<link><successor elementType="road" elementId="nowhere" contactPoint="start"/></link>)"));
    CHECK_THAT(kinds(w), Contains("road link to a missing road") && Contains("'nowhere'"));
  }
  SECTION("lane sections, signals and objects beyond the road's end are dropped") {
    const std::string beyond = R"(<signals><signal id="far" s="4600" t="-4" type="206"
      dynamic="no"/></signals><objects><object id="o" type="pole" s="150" t="-5"/></objects>)";
    const sim::World w = worldOf(roadMap("", "", beyond));
    CHECK_THAT(kinds(w),
               Contains("signal beyond its road's end (dropped)") && Contains("signal far s=4600"));
    CHECK_THAT(kinds(w), Contains("object beyond its road's end (dropped)"));
    CHECK(countOf(w, CrowdClass::kTrafficSign) == 0);
    std::string xml = roadMap();
    xml.replace(xml.find("</lanes>"), 8, R"(<laneSection s="900"><center><lane id="0"/></center>
      </laneSection></lanes>)");
    CHECK_THAT(kinds(worldOf(xml)), Contains("lane section beyond its road's end"));
  }
  SECTION("lane widths: negative taken as 0 with a warning, 1e6 m refused") {
    std::string neg = roadMap();
    neg.replace(neg.find(R"(a="3.5")"), 7, R"(a="-3.07")");
    const sim::World w = worldOf(neg);
    CHECK_THAT(kinds(w), Contains("negative lane width") && Contains("lane 1"));
    CHECK(w.lanes.size() == 1);  // the zero-width left lane is not driven
    std::string wide = roadMap();
    wide.replace(wide.find(R"(a="3.5")"), 7, R"(a="1e6")");
    CHECK_THAT(messageOf(wide), Contains("wild.xodr: field 'road R laneSection s=0 lane 1 width") &&
                                    Contains("beyond 50 m"));
  }
  SECTION("duplicate ids and degenerate geometry are refused") {
    std::string dup = roadMap();
    const std::size_t road = dup.find("<road ");
    const std::size_t end = dup.find("</road>") + 7;
    dup.insert(end, dup.substr(road, end - road));
    CHECK_THAT(messageOf(dup), Contains("road id 'R' appears twice"));
    std::string lanes = roadMap();
    lanes.replace(lanes.find(R"(<lane id="-1")"), 13, R"(<lane id="1")");
    CHECK_THAT(messageOf(lanes), Contains("lane id 1 appears twice"));
    const std::string collapsed =
        R"(<geometry s="0" x="0" y="0" hdg="0" length="100"><paramPoly3 aU="0" bU="0" cU="0"
        dU="0" aV="0" bV="0" cV="0" dV="0" pRange="normalized"/></geometry>)";
    CHECK_THAT(messageOf(roadMap("", collapsed)),
               Contains("road R planView geometry s=0") && Contains("degenerate geometry"));
  }
}

TEST_CASE("OpenDRIVE wild: a road of 2,000 records is looked up by binary search",
          "[sim][opendrive][wild]") {
  // 2,000 half-metre records on a circle of radius 200 m: every lookup must land in the record
  // holding s (a linear scan and a binary search agree; the position is the circle's).
  io::OdrRoad road;
  road.length = 1000.0;
  const double r = 200.0;
  for (int i = 0; i < 2000; ++i) {
    io::OdrGeometry g;
    g.kind = io::OdrGeometry::Kind::kArc;
    g.s = 0.5 * i;
    g.length = 0.5;
    g.curvature = 1.0 / r;
    const double a = g.s / r;
    g.x = r * std::sin(a);
    g.y = r * (1.0 - std::cos(a));
    g.hdg = a;
    road.plan_view.push_back(g);
  }
  const sim::RoadGeometry geo(road);
  for (double s = 0.0; s <= 1000.0; s += 0.37) {
    const sim::RefPose p = geo.reference(s);
    CHECK(std::hypot(p.x - r * std::sin(s / r), p.y - r * (1 - std::cos(s / r))) < kMm);
  }
}

TEST_CASE("simulate --map: no georeference is a local frame, /dev/zero is refused",
          "[sim][opendrive][wild][app]") {
  const fs::path dir = test::tempDir("opendrive_wild_app");
  test::writeText(dir / "local.xodr", roadMap());
  REQUIRE(test::simulateTruthOn(dir, "local.xodr", "", "local") == 0);
  const auto summary = test::readSummary(dir / "local", "simulate");
  const auto& w = summary.at("input_warnings");
  CHECK(w.at("no georeference: map x/y taken as ENU metres about the configured origin")
            .at("count") == 1);
  CHECK(summary.at("world_stats").at("georeferenced") == 0);
  CHECK_THAT(test::readText(dir / "local.err"), Contains("no georeference"));
  // A device is not a map: refused naming it (exit 4), not read to the end of memory.
  const int rc =
      test::runCommand(test::appPath("simulate").string() + " --map /dev/zero --level truth -o " +
                       (dir / "zero").string() + " > /dev/null 2> " + (dir / "zero.err").string());
  CHECK(rc == 4);
  CHECK_THAT(test::readText(dir / "zero.err"), Contains("/dev/zero: is not a regular file"));
}

TEST_CASE("OpenDRIVE wild: every esmini map loads or is refused for its documented reason",
          "[sim][opendrive][wild][shared]") {
  const fs::path corpus = test::requireShared("data/maps/opendrive-esmini");
  // docs/performance-opendrive.md: the one map refused, and why (every road mark `none`).
  const std::map<std::string, std::string> refused = {
      {"xodr__slope_up_leaning_right.xodr", "no true markings"}};
  int maps = 0, loaded = 0;
  for (const auto& entry : fs::directory_iterator(corpus)) {
    if (entry.path().extension() != ".xodr") continue;
    ++maps;
    const std::string name = entry.path().filename().string();
    INFO(name);
    geo::GeoOrigin origin{49.0, 8.4, 0.0};
    try {
      const sim::World w = sim::loadMapWorld(entry.path().string(), true, {}, &origin);
      CHECK(refused.count(name) == 0);
      CHECK(w.stats.at("true_markings") > 0);
      CHECK_FALSE(w.lanes.empty());
      ++loaded;
    } catch (const Error& e) {
      REQUIRE(refused.count(name) == 1);
      CHECK_THAT(e.what(), Contains(name) && Contains(refused.at(name)));
    }
  }
  CHECK(maps == 80);
  CHECK(loaded == maps - static_cast<int>(refused.size()));
}
