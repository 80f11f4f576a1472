#pragma once
/// @file Do two overlapping lane pieces run the same way? Painted lines that cross inside a
/// junction overlap only where they cross, but a short piece (a tile corner cuts lines into bits
/// of a metre) can be covered by the crossing line's buffer, and DBSCAN then chains both lines
/// into one cluster whose centreline zig-zags between them. Pieces whose local directions differ
/// by more than lane `piece_angle_deg` where they come close are therefore not stage-1 neighbours
/// (aggregate/lane_instantiation.cpp).
#include <Eigen/Core>
#include <vector>

namespace mapfuse::aggregate {

/// @brief True when a and b cross: of the points of a (its vertices and samples every `step` m)
/// that lie within `near` m of b, more than half have a local direction that differs by more
/// than `max_angle` (rad, undirected: lines observed in opposite travel directions agree) from
/// that of every segment of b within `near` of them. False when no point of a comes that near.
bool piecesCross(const std::vector<Eigen::Vector2d>& a, const std::vector<Eigen::Vector2d>& b,
                 double near, double max_angle, double step = 0.25);

}  // namespace mapfuse::aggregate
