#pragma once
/// @file Lanelets derived from a vector map's lane lines for the Lanelet2 export (docs/formats.md
/// "Lanelet2 export"). Two lane lines are a lane's bounds where each is the other's nearest line
/// across, a lane width apart (LaneletSettings: 2-5 m) and parallel; every line is cut where a
/// neighbouring lane begins or ends so that side-by-side lanelets begin and end together and
/// consecutive lanelets of one lane share their bounds' end nodes. The travel direction of a
/// lanelet comes from the drives that pass through it (majority of their headings), else from a
/// stop line across its end, else from an oriented neighbour (neighbourDirections); without any it
/// stays unknown (`one_way=no`). Where a drive leaves one lanelet at its end and enters another at
/// its start across an unmarked stretch (an intersection), a connector lanelet with `virtual`
/// bounds joins their bounds' end points (cubic Hermite curves along both lanelets' directions).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <utility>
#include <vector>

#include "mapfuse/core/lsm.hpp"
#include "mapfuse/core/vector_map.hpp"
#include "mapfuse/lanelet/settings.hpp"

namespace mapfuse::lanelet {

/// A drive's path in the map's ENU frame, in driving order (e.g. LSM keyframe positions).
using DrivePath = std::vector<Eigen::Vector3d>;

/// @brief The keyframe paths of drives in the map's frame (LSMs in frame enu of the map).
std::vector<DrivePath> drivePaths(const std::vector<Lsm>& lsms);

struct LaneletPlan {
  /// A lane line with its cut points inserted; pieces run between consecutive cuts.
  struct Line {
    std::size_t instance = 0;             ///< index in VectorMap::instances
    std::vector<Eigen::Vector3d> points;  ///< ENU, m: the instance's points plus cut points
    std::vector<std::size_t> cuts;        ///< vertex indices of the cuts (first and last included)
  };
  /// A piece of a line between two consecutive cuts (a Lanelet2 line string).
  struct Piece {
    std::size_t line = 0;
    std::size_t cut = 0;  ///< the piece runs from cuts[cut] to cuts[cut + 1]
  };
  struct Lanelet {
    std::size_t left = 0, right = 0;      ///< pieces; left of the travel direction when known
    bool direction_known = false;         ///< false: written one_way=no
    int votes_for = 0;                    ///< drive samples inside travelling with the direction
    int votes_against = 0;                ///< ... against it
    std::vector<Eigen::Vector3d> centre;  ///< in the travel direction (or left piece's), m
    std::vector<Eigen::Vector3d> ring;    ///< outline: left bound then right bound reversed
  };
  /// A lanelet across an unmarked stretch, from lanelet `from`'s end to lanelet `to`'s start.
  struct Connector {
    std::size_t from = 0, to = 0;
    std::vector<Eigen::Vector3d> left, right;  ///< bounds in the travel direction, m
    int drives = 0;                            ///< drives that made this connection
  };
  std::vector<Line> lines;  ///< every lane line with at least one lanelet
  std::vector<Piece> pieces;
  std::vector<Lanelet> lanelets;
  std::vector<Connector> connectors;
  int unmatched_pieces = 0;  ///< piece pairs skipped because their cuts did not line up
  int lanelets_oriented_by_neighbours = 0;  ///< direction from a neighbour (neighbourDirections)
  int kink_vertices_removed = 0;            ///< lane-line vertices dropped as kinks (max_curvature)
  double kink_max_deviation = 0.0;     ///< m: farthest dropped vertex from its line's remainder
  int same_side_lanelets_dropped = 0;  ///< a piece bounded two lanelets on one side
  int line_ends_joined = 0;  ///< pairs of facing lane-line ends joined (LaneletSettings::join_gap)
  int one_sided_connections = 0;  ///< drive connections without a connector: bounds met on a side
};

/// @brief Pairs the lane lines of `map` into lanelets; `drives` give travel directions.
LaneletPlan planLanelets(const VectorMap& map, const std::vector<DrivePath>& drives,
                         const LaneletSettings& settings = {});

/// @brief Directions of lanelets without one, from oriented lanelets sharing a bound
/// (right-hand traffic): a lanelet on the right of an oriented one drives its way; one on its
/// left across a solid or yellow line drives the other way (a centre line); across a dashed
/// white line nothing follows (lanes of one direction, or a dashed centre line). Lanelets whose
/// neighbours disagree stay unknown. @return (lanelet, true when its travel direction runs
/// along its `centre` as stored).
std::vector<std::pair<std::size_t, bool>> neighbourDirections(const LaneletPlan& plan,
                                                              const VectorMap& map);

/// @brief The end point of a lanelet's left (or right) bound in the travel direction (`at_end`)
/// or at its start: (piece, true when it is the piece's last point).
std::pair<std::size_t, bool> boundEnd(const LaneletPlan& plan, const LaneletPlan::Lanelet& ll,
                                      bool left, bool at_end);

/// @brief The points of a piece (ENU, m), in its line's order.
std::vector<Eigen::Vector3d> piecePoints(const LaneletPlan& plan, std::size_t piece);

/// @brief A crosswalk outline (a ring of at least 3 points) as a lanelet's two bounds: its
/// longest edge and the opposite chain, so that left + reversed(right) gives the outline back
/// (lanelet/crosswalk.cpp).
std::pair<std::vector<Eigen::Vector3d>, std::vector<Eigen::Vector3d>> crosswalkBounds(
    const std::vector<Eigen::Vector3d>& ring);

/// @brief True when p lies inside the closed ring (xy).
bool insideRingXY(const std::vector<Eigen::Vector3d>& ring, const Eigen::Vector3d& p);

/// @brief The xy bounding box of every lanelet's ring, in lanelet order: a point outside it is
/// outside the ring, so a test of many points against all lanelets reads only the rings whose
/// box holds the point (stop lines against every lanelet cost O(stop lines x lanelets x ring)
/// before: a third of aggregate's time at 119 road km).
std::vector<Eigen::AlignedBox2d> laneletBoxes(const LaneletPlan& plan);

}  // namespace mapfuse::lanelet
