#pragma once
/// @file JSON encodings of geometric values shared by every mapfuse format:
/// points [x, y, z]; poses {"t": [x, y, z], "q": [w, x, y, z]}; origins {"lat", "lon", "alt"};
/// 3x3 covariances as their 6 upper-triangular entries [xx, xy, xz, yy, yz, zz].
#include <vector>

#include "mapfuse/core/classes.hpp"
#include "mapfuse/core/se3.hpp"
#include "mapfuse/geo/origin.hpp"
#include "mapfuse/io/json_view.hpp"

namespace mapfuse::io {

Json vec3ToJson(const Eigen::Vector3d& v);
Json pointsToJson(const std::vector<Eigen::Vector3d>& points);
Json poseToJson(const Pose3& T);
Json originToJson(const geo::GeoOrigin& o);
Json cov3ToJson(const Eigen::Matrix3d& C);

/// @brief Writes "class" and, when set, "style" / "color" into the object `j`.
void writeClassAndAttributes(Json& j, CrowdClass cls, const Attributes& attributes);
/// @brief Reads "class" (required) and "style" / "color" (optional) of an element or instance.
void readClassAndAttributes(const JsonView& v, CrowdClass& cls, Attributes& attributes);

/// @brief Array of [x, y, z] arrays, each coordinate within bounds::kMaxCoordinate.
std::vector<Eigen::Vector3d> readPoints(const JsonView& v);
/// @brief Pose; the quaternion must have unit norm within 1e-3 (then it is normalized), the
/// translation within bounds::kMaxCoordinate.
Pose3 readPose(const JsonView& v);
/// @brief Origin; lat/lon must be valid WGS84, alt within the bounds:: altitude range.
geo::GeoOrigin readOrigin(const JsonView& v);
/// @brief Symmetric 3x3 from 6 entries (each within bounds::kMaxVariance); must be positive
/// semi-definite.
Eigen::Matrix3d readCov3(const JsonView& v);

}  // namespace mapfuse::io
