#pragma once
/// @file A WGS84 point, the type an LSM's GPS fixes and every georeferenced file's origin are
/// made of. Only the type and its validity live here (core holds types); conversions to and
/// from ENU are in mapfuse/geo/origin.hpp.
namespace mapfuse::geo {

/// A WGS84 point: latitude and longitude in degrees, altitude in metres (ellipsoidal).
struct LatLonAlt {
  double lat = 0.0;  ///< deg, [-90, 90]
  double lon = 0.0;  ///< deg, [-180, 180]
  double alt = 0.0;  ///< m
};

/// The origin of a local ENU frame. Every georeferenced file carries one; there is no default.
using GeoOrigin = LatLonAlt;

/// @brief True when lat, lon and alt are finite and lat/lon within their ranges.
bool isValid(const LatLonAlt& p);

}  // namespace mapfuse::geo
