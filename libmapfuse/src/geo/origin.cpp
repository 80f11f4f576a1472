#include "mapfuse/geo/origin.hpp"

#include <sstream>

#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/LocalCartesian.hpp>
#include <cmath>

#include "mapfuse/core/error.hpp"

namespace mapfuse::geo {

std::optional<LatLonAlt> parseLatLonAlt(const std::string& text) {
  std::istringstream is(text);
  LatLonAlt o;
  char c1 = 0, c2 = 0;
  if (!(is >> o.lat >> c1 >> o.lon >> c2 >> o.alt) || c1 != ',' || c2 != ',' ||
      !(is >> std::ws).eof() || !isValid(o))
    return std::nullopt;
  return o;
}

bool sameOrigin(const GeoOrigin& a, const GeoOrigin& b) {
  constexpr double kDegTolerance = 1e-9;
  constexpr double kAltTolerance = 1e-3;  // m
  return std::abs(a.lat - b.lat) <= kDegTolerance && std::abs(a.lon - b.lon) <= kDegTolerance &&
         std::abs(a.alt - b.alt) <= kAltTolerance;
}

struct EnuConverter::Impl {
  GeographicLib::LocalCartesian lc;
};

EnuConverter::EnuConverter(const GeoOrigin& origin) : origin_(origin), impl_(nullptr) {
  if (!isValid(origin))
    throw InputError("invalid ENU origin (lat " + std::to_string(origin.lat) + ", lon " +
                     std::to_string(origin.lon) + ")");
  try {
    impl_ = new Impl{GeographicLib::LocalCartesian(origin.lat, origin.lon, origin.alt)};
  } catch (const GeographicLib::GeographicErr& e) {
    throw InputError(std::string("GeographicLib: ") + e.what());
  }
}

EnuConverter::~EnuConverter() {
  delete impl_;
}
EnuConverter::EnuConverter(const EnuConverter& o) : origin_(o.origin_), impl_(new Impl(*o.impl_)) {}
EnuConverter& EnuConverter::operator=(const EnuConverter& o) {
  if (this != &o) {
    delete impl_;
    origin_ = o.origin_;
    impl_ = new Impl(*o.impl_);
  }
  return *this;
}

Eigen::Vector3d EnuConverter::toEnu(const LatLonAlt& p) const {
  double x, y, z;
  impl_->lc.Forward(p.lat, p.lon, p.alt, x, y, z);
  return {x, y, z};
}

LatLonAlt EnuConverter::toWgs84(const Eigen::Vector3d& enu) const {
  LatLonAlt p;
  impl_->lc.Reverse(enu.x(), enu.y(), enu.z(), p.lat, p.lon, p.alt);
  return p;
}

Eigen::Isometry3d reexpressPose(const Eigen::Isometry3d& T_from_body, const EnuConverter& from,
                                const EnuConverter& to) {
  const Eigen::Vector3d p = T_from_body.translation();
  const Eigen::Vector3d q = to.toEnu(from.toWgs84(p));
  Eigen::Matrix3d R_to_from;  // column i: the from-frame axis i seen in the to-frame
  for (int i = 0; i < 3; ++i)
    R_to_from.col(i) = to.toEnu(from.toWgs84(p + Eigen::Vector3d::Unit(i))) - q;
  const Eigen::Quaterniond rot(R_to_from);  // nearest rotation up to ~1e-9 rad
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = rot.normalized().toRotationMatrix() * T_from_body.linear();
  out.translation() = q;
  return out;
}

double geodesicDistance(const LatLonAlt& a, const LatLonAlt& b) {
  double s12 = 0.0;
  GeographicLib::Geodesic::WGS84().Inverse(a.lat, a.lon, b.lat, b.lon, s12);
  return s12;
}

}  // namespace mapfuse::geo
