#pragma once
/// @file Geodetic origin of a local ENU frame. Every georeferenced file carries one explicitly;
/// there is no default origin.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <string>

#include "mapfuse/core/lat_lon_alt.hpp"

namespace mapfuse::geo {

/// @brief Parses "lat,lon,alt" (degrees, degrees, metres); nullopt unless it is exactly three
/// numbers forming a valid point.
std::optional<LatLonAlt> parseLatLonAlt(const std::string& text);

/// @brief Two origins are the same when they agree within 1e-9 deg and 1 mm.
bool sameOrigin(const GeoOrigin& a, const GeoOrigin& b);

/// Converts between WGS84 and East-North-Up metres about one origin (GeographicLib's
/// LocalCartesian: exact ellipsoidal transform, not a flat-earth approximation).
class EnuConverter {
 public:
  /// @throws InputError when the origin is not a valid WGS84 point.
  explicit EnuConverter(const GeoOrigin& origin);
  ~EnuConverter();
  EnuConverter(const EnuConverter&);
  EnuConverter& operator=(const EnuConverter&);

  const GeoOrigin& origin() const { return origin_; }
  Eigen::Vector3d toEnu(const LatLonAlt& p) const;
  LatLonAlt toWgs84(const Eigen::Vector3d& enu) const;

 private:
  struct Impl;
  GeoOrigin origin_;
  Impl* impl_;
};

/// @brief The same body pose expressed in the ENU frame of another origin: T_to_body from
/// T_from_body. The position goes through WGS84; the orientation turns with the rotation
/// between the two local ENU frames (meridian convergence and the tilt of the local vertical,
/// ~1e-4 rad per km), taken from the converted unit axes and orthonormalised.
Eigen::Isometry3d reexpressPose(const Eigen::Isometry3d& T_from_body, const EnuConverter& from,
                                const EnuConverter& to);

/// @brief Rotation (radians, counter-clockwise from East) between local grid north and true
/// north is ignored by ENU; this returns the great-circle distance in metres between two points
/// (GeographicLib geodesic), used by tests and summaries.
double geodesicDistance(const LatLonAlt& a, const LatLonAlt& b);

}  // namespace mapfuse::geo
