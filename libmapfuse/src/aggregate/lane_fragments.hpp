#pragma once
/// @file Stage-1 lane fragments (one DBSCAN cluster of observation pieces each) and the merges
/// that repair what cutting observations at tile edges did to them, before stage-2 linking
/// (lane_instantiation.cpp).
#include <Eigen/Core>
#include <set>
#include <vector>

#include "lane_instantiation.hpp"

namespace mapfuse::aggregate {

struct Fragment {
  std::vector<Eigen::Vector3d> centreline;  ///< binned along the principal axis
  std::vector<Eigen::Vector3d> samples;     ///< resampled member points
  std::set<std::size_t> obs;                ///< observations the member pieces came from
};

/// Merges fragments of one line split by a tile edge running along it (side by side: half of
/// either centreline within 2 x buffer_width of the other).
void mergeSideBySide(std::vector<Fragment>& frags, const LaneInstantiationParams& p);

/// A stub -- a fragment shorter than one station (station_step), mostly the bit of a dash a
/// tile edge cut off -- joins the nearest longer fragment within one station. Left alone, its
/// direction is undefined, so it became a second follower of its neighbours' ends and, by the
/// MaxPts rule, broke their stage-2 links: dashed lines fell apart and lost whole dashes.
void absorbStubs(std::vector<Fragment>& frags, const LaneInstantiationParams& p);

}  // namespace mapfuse::aggregate
