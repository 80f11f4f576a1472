#include "mapfuse/geo/map_projection.hpp"

#include <GeographicLib/TransverseMercator.hpp>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>

#include "mapfuse/core/error.hpp"

namespace mapfuse::geo {

namespace {

double number(const std::string& proj, const std::string& key, const std::string& value) {
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(value.c_str(), &end);
  if (value.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(v))
    throw InputError("georeference '" + proj + "': +" + key + "=" + value + " is not a number");
  return v;
}

}  // namespace

MapProjection MapProjection::fromProj(const std::string& proj) {
  auto fail = [&](const std::string& problem) -> void {
    throw InputError("georeference '" + proj + "': " + problem +
                     " (supported: +proj=tmerc or +proj=utm on WGS84 / GRS80, metres)");
  };
  std::map<std::string, std::string> p;
  std::istringstream in(proj);
  for (std::string tok; in >> tok;) {
    if (tok.empty() || tok[0] != '+') fail("'" + tok + "' is not a +key=value parameter");
    const auto eq = tok.find('=');
    p[tok.substr(1, eq == std::string::npos ? std::string::npos : eq - 1)] =
        eq == std::string::npos ? "" : tok.substr(eq + 1);
  }
  // The projection first: a foreign projection's own parameters are not the problem to name.
  const std::string name = p.count("proj") ? p.at("proj") : "";
  if (name != "tmerc" && name != "utm")
    fail(name.empty() ? "no +proj" : "projection '" + name + "' is not supported");
  static const char* const kKnown[] = {"proj",    "lat_0", "lon_0",      "k",      "k_0",
                                       "x_0",     "y_0",   "ellps",      "datum",  "units",
                                       "no_defs", "type",  "geoidgrids", "vunits", "towgs84",
                                       "zone",    "south", "wktext",     "axis"};
  for (const auto& [key, value] : p) {
    bool known = false;
    for (const char* k : kKnown) known |= key == k;
    if (!known) fail("parameter +" + key + " is not supported");
  }
  MapProjection m;
  const std::string ellps = p.count("ellps")   ? p.at("ellps")
                            : p.count("datum") ? p.at("datum")
                                               : "";
  if (ellps == "GRS80") {
    m.f_ = 1.0 / 298.257222101;
    m.ellipsoid_ = "GRS80";
  } else if (ellps != "WGS84") {
    fail(ellps.empty() ? "no +ellps or +datum" : "ellipsoid '" + ellps + "' is not supported");
  }
  if (p.count("units") && p.at("units") != "m") fail("+units=" + p.at("units") + " is not metres");
  if (p.count("axis") && p.at("axis") != "enu") fail("+axis=" + p.at("axis") + " is not enu");
  if (p.count("towgs84")) {
    std::istringstream t(p.at("towgs84"));
    for (std::string v; std::getline(t, v, ',');)
      if (number(proj, "towgs84", v) != 0.0) fail("a datum shift (+towgs84) is not supported");
  }
  auto get = [&](const char* key, double fallback) {
    return p.count(key) ? number(proj, key, p.at(key)) : fallback;
  };
  if (name == "tmerc") {
    m.lat0_ = get("lat_0", 0.0);
    m.lon0_ = get("lon_0", 0.0);
    m.k0_ = p.count("k") ? get("k", 1.0) : get("k_0", 1.0);
    m.x0_ = get("x_0", 0.0);
    m.y0_ = get("y_0", 0.0);
  } else if (name == "utm") {
    const double zone = get("zone", 0.0);
    if (zone < 1 || zone > 60 || zone != std::floor(zone)) fail("+zone must be 1..60");
    m.name_ = "utm";
    m.lon0_ = 6.0 * zone - 183.0;
    m.k0_ = 0.9996;
    m.x0_ = 500000.0;
    m.y0_ = p.count("south") ? 10000000.0 : 0.0;
  }
  if (std::abs(m.lat0_) > 90 || std::abs(m.lon0_) > 180 || !(m.k0_ > 0))
    fail("lat_0 / lon_0 / k out of range");
  const GeographicLib::TransverseMercator tm(m.a_, m.f_, m.k0_);
  double x = 0, y = 0;
  tm.Forward(m.lon0_, m.lat0_, m.lon0_, x, y);
  m.northing_at_lat0_ = y;
  return m;
}

LatLonAlt MapProjection::toWgs84(double x, double y, double z) const {
  const GeographicLib::TransverseMercator tm(a_, f_, k0_);
  LatLonAlt g;
  tm.Reverse(lon0_, x - x0_, y - y0_ + northing_at_lat0_, g.lat, g.lon);
  g.alt = z;
  return g;
}

Eigen::Vector2d MapProjection::fromWgs84(double lat, double lon) const {
  const GeographicLib::TransverseMercator tm(a_, f_, k0_);
  double x = 0, y = 0;
  tm.Forward(lon0_, lat, lon, x, y);
  return {x + x0_, y - northing_at_lat0_ + y0_};
}

std::string MapProjection::describe() const {
  std::ostringstream o;
  o.precision(12);
  o << name_ << " lat_0=" << lat0_ << " lon_0=" << lon0_ << " k=" << k0_ << " x_0=" << x0_
    << " y_0=" << y0_ << " (" << ellipsoid_ << ")";
  return o.str();
}

}  // namespace mapfuse::geo
