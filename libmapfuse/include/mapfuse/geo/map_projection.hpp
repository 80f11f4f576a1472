#pragma once
/// @file Map projections of georeferenced map files (docs/simulate.md "OpenDRIVE maps"): the
/// PROJ string of an OpenDRIVE header turned into a transverse Mercator projection
/// (GeographicLib::TransverseMercator, Krueger series, 5 nm accuracy) between the map's x/y
/// metres and WGS84. Supported: `+proj=tmerc` (lat_0, lon_0, k / k_0 in [0.1, 10], x_0, y_0) and
/// `+proj=utm` (zone, south) on the WGS84 or GRS80 ellipsoid (GRS80 / ETRS89 is taken as WGS84:
/// < 1 m), on any ellipsoid given by +a with +b / +rf / +f, or on a sphere (+R, +a alone,
/// +ellps=sphere; its lat/lon used as WGS84, as PROJ does with +nadgrids=@null). Harmless
/// parameters (+units=m, +no_defs, +wktext, +nadgrids=@null, +towgs84=0,0,0, vertical grids) are
/// accepted and ignored. Anything else (another projection, ellipsoid, unit, a datum shift, an
/// EPSG code) is an InputError naming the file and the part that is not supported, never a
/// silently wrong position.
#include <Eigen/Core>
#include <string>

#include "mapfuse/core/lat_lon_alt.hpp"

namespace mapfuse::geo {

class MapProjection {
 public:
  /// @brief Parses a PROJ string ("+proj=tmerc +lat_0=48.1 +lon_0=11.5 +k=1 +x_0=0 +y_0=0
  /// +datum=WGS84 +units=m"). Vertical parameters (geoidgrids, vunits) are accepted and ignored:
  /// heights stay as the map states them.
  /// @param source the file it comes from, named first in errors ("" for none).
  /// @throws InputError naming the file, the string and the unsupported parameter.
  static MapProjection fromProj(const std::string& proj, const std::string& source = "");

  /// @brief WGS84 of map coordinates (m); alt = z.
  LatLonAlt toWgs84(double x, double y, double z) const;
  /// @brief Map coordinates (m) of a WGS84 point.
  Eigen::Vector2d fromWgs84(double lat, double lon) const;
  /// @brief "tmerc lat_0=... lon_0=... k=... x_0=... y_0=... (WGS84)".
  std::string describe() const;

 private:
  double a_ = 6378137.0, f_ = 1.0 / 298.257223563, k0_ = 1.0;
  double lat0_ = 0.0, lon0_ = 0.0, x0_ = 0.0, y0_ = 0.0;
  double northing_at_lat0_ = 0.0;  ///< projected y of (lat_0, lon_0) before y_0
  std::string name_ = "tmerc", ellipsoid_ = "WGS84";
};

}  // namespace mapfuse::geo
