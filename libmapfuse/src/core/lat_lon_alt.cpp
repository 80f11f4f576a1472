#include "mapfuse/core/lat_lon_alt.hpp"

#include <cmath>

namespace mapfuse::geo {

bool isValid(const LatLonAlt& p) {
  return std::isfinite(p.lat) && std::isfinite(p.lon) && std::isfinite(p.alt) &&
         std::abs(p.lat) <= 90.0 && std::abs(p.lon) <= 180.0;
}

}  // namespace mapfuse::geo
