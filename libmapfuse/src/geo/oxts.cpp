#include "mapfuse/geo/oxts.hpp"

#include <cmath>


namespace mapfuse::geo {
double mercatorScale(double lat0_deg) {
  return std::cos(lat0_deg * M_PI / 180.0);
}

Pose3 oxtsToMercatorPose(const OxtsRecord& r, double scale) {
  const double tx = scale * r.lon * M_PI * kKittiEarthRadius / 180.0;
  const double ty = scale * kKittiEarthRadius * std::log(std::tan((90.0 + r.lat) * M_PI / 360.0));
  return poseFromXyzRpy(tx, ty, r.alt, r.roll, r.pitch, r.yaw);
}

Pose3 oxtsToEnuPose(const OxtsRecord& r, const EnuConverter& enu) {
  const Eigen::Vector3d t = enu.toEnu({r.lat, r.lon, r.alt});
  return poseFromXyzRpy(t.x(), t.y(), t.z(), r.roll, r.pitch, r.yaw);
}

}  // namespace mapfuse::geo
