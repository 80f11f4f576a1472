#pragma once
/// @file OpenDRIVE road geometry (ASAM OpenDRIVE 1.6, sections 7-9; docs/simulate.md
/// "OpenDRIVE maps"): the reference line of every plan-view record (line, arc, clothoid spiral
/// through Fresnel integrals, poly3 by arc length, paramPoly3), elevation, superelevation, the
/// lane offset and lane borders from lane widths, in the map's projected x/y/z metres.
#include <Eigen/Core>
#include <vector>

#include "mapfuse/io/opendrive.hpp"

namespace mapfuse::sim {

/// @brief Fresnel integrals C(x) = int_0^x cos(pi t^2 / 2) dt and S(x) = int_0^x sin(pi t^2 / 2)
/// dt: power series for |x| <= 1.5, else the complex continued fraction of erfc (modified
/// Lentz), both to about 1e-15.
void fresnel(double x, double* C, double* S);

/// A point of a reference line: position (m) and heading (rad).
struct RefPose {
  double x = 0.0, y = 0.0, hdg = 0.0;
};

/// @brief The reference line of one plan-view record at ds in [0, length] from its start.
/// Spiral: curvature k(ds) = k0 + (k1 - k0) ds / length, position from Fresnel integrals.
/// paramPoly3: p = ds / length (normalized) or ds (arcLength). poly3: v(u) in the local frame,
/// u found from the arc length ds (Simpson table and Newton steps).
RefPose evalGeometry(const io::OdrGeometry& g, double ds);

/// Evaluates one road: reference line, heights and lane borders at (s, t).
class RoadGeometry {
 public:
  explicit RoadGeometry(const io::OdrRoad& road);

  /// @brief Reference-line pose at s (clamped to [0, length]).
  RefPose reference(double s) const;
  /// @brief A point at (s, t) in map metres: reference line, `t` to the left along the normal
  /// (rolled by the superelevation), z = elevation + t sin(superelevation).
  Eigen::Vector3d point(double s, double t) const;
  /// @brief The lane offset (shift of the centre lane) at s, m.
  double laneOffset(double s) const;
  /// @brief t of the outer border of lane `id` of section `section` at s (id 0: the centre
  /// lane's line, i.e. the lane offset).
  double borderT(std::size_t section, int id, double s) const;
  /// @brief Width of lane `id` of `section` at s (0 for the centre lane or an unknown lane).
  double laneWidth(std::size_t section, int id, double s) const;
  /// @brief Start and end s of a lane section.
  double sectionStart(std::size_t section) const;
  double sectionEnd(std::size_t section) const;
  const io::OdrRoad& road() const { return road_; }

 private:
  const io::OdrRoad& road_;
  /// poly3 records: ds -> u tables (arc length at uniform u samples)
  std::vector<std::vector<double>> poly3_arc_;
};

}  // namespace mapfuse::sim
