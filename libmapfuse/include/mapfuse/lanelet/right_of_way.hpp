#pragma once
/// @file Right of way at the intersections of a Lanelet2 export (docs/formats.md "Lanelet2
/// export", Lanelet2's RegulatoryElementTagging.md "Right of Way" and "All Way Stop"). The crowd
/// map does not know which sign a plate shows, so the rule is read from the stop lines alone:
/// - approaches: one-way lanelets that end at an intersection: no oriented lanelet continues
///   them (none is bounded by the next pieces of both their bounds' lines), a connector (a drive
///   through an unmarked stretch) leaves their end, or a stop line crosses them within 8 m of
///   their end; an approach's stop line is the one its axis meets nearest to its end, from 8 m
///   before to 10 m beyond it (the lane lines may run on a little past the last lanelet);
///   approaches whose ends lie within 40 m (LaneletSettings::intersection_reach) of each other
///   (single linkage) are one intersection;
/// - an intersection with a traffic light within 25 m (regulatory_reach) of one of its stop lines
/// is left to the
///   lights;
/// - approaches cross when their directions are 30-150 degrees apart;
/// - one where approaches without a stop line cross approaches with one: the stop-line
///   approaches yield (`yield`, their stop lines `ref_line` in the same order) to those crossing
///   free approaches (`right_of_way`): a `right_of_way` element;
/// - otherwise, when stop-line approaches cross each other: an `all_way_stop` element (`yield`,
///   `ref_line` in the same order, `refers` = the signs at those stop lines); free approaches
///   parallel to every stop-line approach (a lane beside them, a lane ending down the road)
///   decide nothing;
/// - a stop line on a straight road (a crosswalk, a bridge) crosses nothing and regulates
///   nothing here.
/// A stop line the crowd missed makes its approach look free, so a free approach counts only
/// when a drive passed its end (within 10 m, in its direction): an intersection with a
/// crossing free approach no drive passed gets no rule. A stop line missed on a driven approach
/// still turns an all-way stop into right of way; the export's summary counts both kinds.
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "mapfuse/lanelet/plan.hpp"

namespace mapfuse::lanelet {

/// A stop line of the map.
struct RightOfWayStop {
  std::vector<Eigen::Vector3d> points;  ///< the stop line (ENU, m)
  bool signalled = false;               ///< a traffic light stands within 25 m of it
};

/// The right-of-way rule of one intersection.
struct RightOfWayRule {
  bool all_way_stop = false;              ///< every approach has a stop line
  std::vector<std::size_t> yield;         ///< approach lanelets that yield (plan indices)
  std::vector<std::size_t> yield_stop;    ///< per yield lanelet: its stop line (index in stops)
  std::vector<std::size_t> right_of_way;  ///< approach lanelets with right of way
};

/// @brief The rules of every intersection of `plan` that the stop lines make derivable;
/// `drives` (the map's ENU paths) show which free approaches were driven through.
std::vector<RightOfWayRule> deriveRightOfWay(const LaneletPlan& plan,
                                             const std::vector<RightOfWayStop>& stops,
                                             const std::vector<DrivePath>& drives,
                                             const LaneletSettings& settings = {});

}  // namespace mapfuse::lanelet
