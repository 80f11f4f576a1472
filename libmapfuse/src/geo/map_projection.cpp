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

/// Bounds of a representable georeference (docs/simulate.md "Georeference"): the ellipsoid's
/// axes are an Earth radius (m), the scale factor a map scale (k = 1e300 made every point
/// infinite), the false easting / northing within 1e8 m.
constexpr double kMinEarthAxis = 6.0e6, kMaxEarthAxis = 6.6e6;
constexpr double kMinScale = 0.1, kMaxScale = 10.0;
constexpr double kMaxFalseOffset = 1e8;

/// Parameters accepted and ignored: they change nothing for a metric tmerc / utm georeference
/// (units=m and axis=enu are checked, towgs84 must be all zeros, nadgrids must be @null).
const char* const kIgnored[] = {"no_defs", "type", "geoidgrids", "vunits", "wktext", "over"};
const char* const kKnown[] = {"proj",  "lat_0", "lon_0", "k",       "k_0",  "x_0",     "y_0",
                              "ellps", "datum", "units", "towgs84", "zone", "south",   "axis",
                              "a",     "b",     "R",     "rf",      "f",    "nadgrids"};

struct ProjText {
  std::string proj, source;
  std::map<std::string, std::string> p;

  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError((source.empty() ? "" : source + ": ") + "georeference '" + proj +
                     "': " + problem +
                     " (supported: +proj=tmerc or +proj=utm on WGS84 / GRS80 or a sphere, "
                     "metres; docs/simulate.md \"Georeference\")");
  }
  bool has(const char* key) const { return p.count(key) > 0; }
  double number(const std::string& key, const std::string& value) const {
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(value.c_str(), &end);
    if (value.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(v))
      fail("+" + key + "=" + value + " is not a number");
    return v;
  }
  double get(const char* key, double fallback) const {
    return has(key) ? number(key, p.at(key)) : fallback;
  }
  double within(const char* key, double fallback, double lo, double hi, const char* what) const {
    const double v = get(key, fallback);
    if (!(v >= lo && v <= hi)) {
      std::ostringstream o;
      o << "+" << key << "=" << p.at(key) << " is outside [" << lo << ", " << hi << "] (" << what
        << ")";
      fail(o.str());
    }
    return v;
  }
};

ProjText tokenize(const std::string& proj, const std::string& source) {
  ProjText t{proj, source, {}};
  std::istringstream in(proj);
  for (std::string tok; in >> tok;) {
    if (tok.empty() || tok[0] != '+') t.fail("'" + tok + "' is not a +key=value parameter");
    const auto eq = tok.find('=');
    t.p[tok.substr(1, eq == std::string::npos ? std::string::npos : eq - 1)] =
        eq == std::string::npos ? "" : tok.substr(eq + 1);
  }
  // The projection first: a foreign projection's own parameters are not the problem to name.
  const std::string name = t.has("proj") ? t.p.at("proj") : "";
  if (name != "tmerc" && name != "utm")
    t.fail(name.empty() ? "no +proj" : "projection '" + name + "' is not supported");
  for (const auto& [key, value] : t.p) {
    bool known = false;
    for (const char* k : kKnown) known |= key == k;
    for (const char* k : kIgnored) known |= key == k;
    if (!known) t.fail("parameter +" + key + " is not supported");
  }
  if (t.has("units") && t.p.at("units") != "m")
    t.fail("+units=" + t.p.at("units") + " is not metres");
  if (t.has("axis") && t.p.at("axis") != "enu") t.fail("+axis=" + t.p.at("axis") + " is not enu");
  if (t.has("nadgrids") && t.p.at("nadgrids") != "@null")
    t.fail("a datum grid shift (+nadgrids=" + t.p.at("nadgrids") + ") is not supported");
  if (t.has("towgs84")) {
    std::istringstream s(t.p.at("towgs84"));
    for (std::string v; std::getline(s, v, ',');)
      if (t.number("towgs84", v) != 0.0) t.fail("a datum shift (+towgs84) is not supported");
  }
  return t;
}

/// Semi-major axis a, flattening f and a name: +a with +b / +rf / +f (or alone: a sphere), +R (a
/// sphere), +ellps / +datum (WGS84, GRS80, PROJ's `sphere`), else PROJ's default GRS80. Lat/lon on
/// a sphere are used as WGS84 lat/lon, as PROJ does with +nadgrids=@null (no datum shift).
void ellipsoid(const ProjText& t, double* a, double* f, std::string* name) {
  auto axis = [&](const char* key) {
    return t.within(key, 0.0, kMinEarthAxis, kMaxEarthAxis, "an Earth radius in metres");
  };
  if (t.has("R")) {
    *a = axis("R"), *f = 0.0, *name = "sphere R=" + t.p.at("R");
    return;
  }
  if (t.has("a")) {
    *a = axis("a");
    if (t.has("b")) {
      const double b = axis("b");
      if (b > *a) t.fail("+b is larger than +a");
      *f = (*a - b) / *a;
    } else if (t.has("rf")) {
      *f = 1.0 / t.within("rf", 0.0, 100.0, 1e12, "an inverse flattening");
    } else if (t.has("f")) {
      *f = t.within("f", 0.0, 0.0, 0.01, "a flattening");
    } else {
      *f = 0.0;
    }
    *name = *f == 0.0 ? "sphere a=" + t.p.at("a") : "a=" + t.p.at("a") + " f=" + std::to_string(*f);
    return;
  }
  const std::string ellps = t.has("ellps")   ? t.p.at("ellps")
                            : t.has("datum") ? t.p.at("datum")
                                             : "";
  if (t.has("datum") && t.p.at("datum") != "WGS84")
    t.fail("datum '" + t.p.at("datum") + "' is not supported (WGS84)");
  *a = 6378137.0;
  if (ellps == "WGS84") {
    *f = 1.0 / 298.257223563, *name = "WGS84";
  } else if (ellps == "GRS80" || ellps.empty()) {  // PROJ's default ellipsoid is GRS80
    *f = 1.0 / 298.257222101, *name = "GRS80";
  } else if (ellps == "sphere") {
    *a = 6370997.0, *f = 0.0, *name = "sphere R=6370997";
  } else {
    t.fail("ellipsoid '" + ellps + "' is not supported");
  }
}

}  // namespace

MapProjection MapProjection::fromProj(const std::string& proj, const std::string& source) {
  const ProjText t = tokenize(proj, source);
  MapProjection m;
  ellipsoid(t, &m.a_, &m.f_, &m.ellipsoid_);
  if (t.p.at("proj") == "tmerc") {
    m.lat0_ = t.within("lat_0", 0.0, -90.0, 90.0, "degrees");
    m.lon0_ = t.within("lon_0", 0.0, -180.0, 180.0, "degrees");
    m.k0_ = t.has("k") ? t.within("k", 1.0, kMinScale, kMaxScale, "a map scale factor")
                       : t.within("k_0", 1.0, kMinScale, kMaxScale, "a map scale factor");
    m.x0_ = t.within("x_0", 0.0, -kMaxFalseOffset, kMaxFalseOffset, "metres");
    m.y0_ = t.within("y_0", 0.0, -kMaxFalseOffset, kMaxFalseOffset, "metres");
  } else {  // utm: zone and hemisphere fix lon_0, k, x_0 and y_0 (PROJ ignores the others)
    const double zone = t.get("zone", 0.0);
    if (zone < 1 || zone > 60 || zone != std::floor(zone)) t.fail("+zone must be 1..60");
    m.name_ = "utm";
    m.lon0_ = 6.0 * zone - 183.0;
    m.k0_ = 0.9996;
    m.x0_ = 500000.0;
    m.y0_ = t.has("south") ? 10000000.0 : 0.0;
  }
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
