#pragma once
// Straight lane lines and checks on a lanelet plan, for the lanelet tests (test_line_joins.cpp,
// test_connectors.cpp).
#include <catch2/catch.hpp>

#include <vector>

#include "mapfuse/lanelet/plan.hpp"

namespace mapfuse::test {

using Line = std::vector<Eigen::Vector3d>;

/// A straight lane line at height y from x0 to x1, a vertex every metre (and at x1).
inline Line straight(double y, double x0, double x1) {
  Line pts;
  for (double x = x0; x < x1 - 1e-9; x += 1.0) pts.push_back({x, y, 0.0});
  pts.push_back({x1, y, 0.0});
  return pts;
}

/// A map of lane lines, instance i holding lines[i].
inline VectorMap mapOf(const std::vector<Line>& lines) {
  VectorMap map;
  for (const auto& pts : lines) {
    MapInstance m;
    m.id = static_cast<int64_t>(map.instances.size() + 1);
    m.points = pts;
    map.instances.push_back(m);
  }
  return map;
}

/// No connector has a bound whose two ends are one point (a one-node way in the OSM).
inline void requireNoDegenerateConnector(const lanelet::LaneletPlan& plan) {
  for (const auto& c : plan.connectors) {
    CHECK((c.left.front() - c.left.back()).norm() > 0.1);
    CHECK((c.right.front() - c.right.back()).norm() > 0.1);
  }
}

}  // namespace mapfuse::test
