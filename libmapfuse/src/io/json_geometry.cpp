#include "mapfuse/io/json_geometry.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace mapfuse::io {

Json vec3ToJson(const Eigen::Vector3d& v) {
  return Json::array({v.x(), v.y(), v.z()});
}

Json pointsToJson(const std::vector<Eigen::Vector3d>& points) {
  Json a = Json::array();
  for (const auto& p : points) a.push_back(vec3ToJson(p));
  return a;
}

Json poseToJson(const Pose3& T) {
  const Eigen::Quaterniond q(T.linear());
  return {{"t", vec3ToJson(T.translation())}, {"q", Json::array({q.w(), q.x(), q.y(), q.z()})}};
}

Json originToJson(const geo::GeoOrigin& o) {
  return {{"lat", o.lat}, {"lon", o.lon}, {"alt", o.alt}};
}

Json cov3ToJson(const Eigen::Matrix3d& C) {
  return Json::array({C(0, 0), C(0, 1), C(0, 2), C(1, 1), C(1, 2), C(2, 2)});
}

void writeClassAndAttributes(Json& j, CrowdClass cls, const Attributes& attributes) {
  j["class"] = crowdClassName(cls);
  if (attributes.style != LineStyle::kNone) j["style"] = lineStyleName(attributes.style);
  if (attributes.color != LineColor::kNone) j["color"] = lineColorName(attributes.color);
}

void readClassAndAttributes(const JsonView& v, CrowdClass& cls, Attributes& attributes) {
  const std::string name = v.at("class").string();
  const auto c = crowdClassFromName(name);
  if (!c) v.at("class").fail("unknown class '" + name + "'");
  cls = *c;
  if (auto s = v.find("style")) {
    const auto style = lineStyleFromName(s->string());
    if (!style) s->fail("unknown line style '" + s->string() + "'");
    attributes.style = *style;
  }
  if (auto s = v.find("color")) {
    const auto color = lineColorFromName(s->string());
    if (!color) s->fail("unknown line colour '" + s->string() + "'");
    attributes.color = *color;
  }
}

std::vector<Eigen::Vector3d> readPoints(const JsonView& v) {
  std::vector<Eigen::Vector3d> points(v.size());
  for (std::size_t i = 0; i < points.size(); ++i) points[i] = v.at(i).coordinate();
  return points;
}

Pose3 readPose(const JsonView& v) {
  v.onlyKeys({"t", "q"});
  const Eigen::VectorXd q = v.at("q").vector(4);
  if (std::abs(q.norm() - 1.0) > 1e-3)
    v.at("q").fail("quaternion norm is " + std::to_string(q.norm()) + ", expected 1");
  Pose3 T = Pose3::Identity();
  T.linear() = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
  T.translation() = v.at("t").coordinate();
  return T;
}

geo::GeoOrigin readOrigin(const JsonView& v) {
  v.onlyKeys({"lat", "lon", "alt"});
  return geo::GeoOrigin{v.at("lat").number(-90.0, 90.0), v.at("lon").number(-180.0, 180.0),
                        v.at("alt").number(bounds::kMinAltitude, bounds::kMaxAltitude)};
}

Eigen::Matrix3d readCov3(const JsonView& v) {
  const Eigen::VectorXd c = v.vector(6);
  for (int i = 0; i < 6; ++i)
    if (std::abs(c[i]) > bounds::kMaxVariance)
      v.at(std::size_t(i))
          .fail("covariance entry outside " +
                bounds::rangeText(-bounds::kMaxVariance, bounds::kMaxVariance));
  Eigen::Matrix3d C;
  C << c[0], c[1], c[2], c[1], c[3], c[4], c[2], c[4], c[5];
  const double min_eig = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(C).eigenvalues().minCoeff();
  if (min_eig < -1e-9 * std::max(1.0, C.norm())) v.fail("covariance is not positive semi-definite");
  return C;
}

}  // namespace mapfuse::io
