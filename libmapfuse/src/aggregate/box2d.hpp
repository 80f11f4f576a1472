#pragma once
/// @file The horizontal (EN) Boost.Geometry box of a point set grown by a margin: the R-tree key
/// of lane observation pieces and of stage-1 fragments (lane_instantiation.cpp,
/// lane_fragments.cpp).
#include <Eigen/Core>
#include <boost/geometry/algorithms/expand.hpp>
#include <boost/geometry/geometries/box.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <vector>

namespace mapfuse::aggregate {

using P2 = boost::geometry::model::d2::point_xy<double>;
using Box2 = boost::geometry::model::box<P2>;

inline Box2 boxOf(const std::vector<Eigen::Vector3d>& pts, double margin) {
  Box2 b(P2(pts[0].x(), pts[0].y()), P2(pts[0].x(), pts[0].y()));
  for (const auto& p : pts) boost::geometry::expand(b, P2(p.x(), p.y()));
  return Box2(P2(b.min_corner().x() - margin, b.min_corner().y() - margin),
              P2(b.max_corner().x() + margin, b.max_corner().y() + margin));
}

}  // namespace mapfuse::aggregate
