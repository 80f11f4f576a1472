#pragma once
/// @file The tunable thresholds of the Lanelet2 export's inference (docs/formats.md "Lanelet2
/// export"): how lane lines pair into lanelets, how drives connect them across intersections,
/// how far a stop line, light or sign reaches. Defaults are those of the maps in docs/results.md.
#include "mapfuse/core/param.hpp"

namespace mapfuse::lanelet {

struct LaneletSettings {
  double min_width = 2.0;            ///< m; a closer neighbour line blocks (double lines)
  double max_width = 5.0;            ///< m; a farther line bounds no lanelet with this one
  double min_length = 4.0;           ///< m; shorter paired stretches give no lanelet
  double stop_line_end = 6.0;        ///< m; a stop line this close to a lanelet end orients it
  double max_connector = 60.0;       ///< m of unmarked drive between two lanelets
  double intersection_reach = 40.0;  ///< m between the ends of one intersection's approaches
  double regulatory_reach = 25.0;    ///< m from a stop line's middle to its lights and signs
  double lone_reach = 15.0;          ///< m from a light or sign without stop line to its lanelet
  double max_curvature = 0.4;        ///< 1/m; sharper lane-line vertices are kinks (kinks.hpp)
  double join_gap = 3.0;  ///< m; facing lane-line ends this close continue one line (joins.hpp)

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("lanelet_min_width", min_width, "m",
      "Lanelet2 export: narrowest lane (closer lane lines bound no lanelet)", in(0.5, 10));
    v("lanelet_max_width", max_width, "m",
      "Lanelet2 export: widest lane (farther lane lines bound no lanelet)", in(1, 20));
    v.relation("lanelet_max_width", max_width, max_width > min_width, "> lanelet_min_width");
    v("lanelet_min_length", min_length, "m",
      "Lanelet2 export: shortest stretch of two paired lane lines that makes a lanelet",
      in(0.5, 100));
    v("lanelet_stop_line_end", stop_line_end, "m",
      "Lanelet2 export: a stop line this close to a lanelet's end gives its direction", in(0, 50));
    v("lanelet_max_connector", max_connector, "m",
      "Lanelet2 export: longest unmarked drive joining two lanelets (intersections)", in(1, 500));
    v("lanelet_intersection_reach", intersection_reach, "m",
      "Lanelet2 export: approaches ending this close together are one intersection", in(1, 500));
    v("lanelet_regulatory_reach", regulatory_reach, "m",
      "Lanelet2 export: reach from a stop line to the lights and signs it belongs to", in(1, 200));
    v("lanelet_lone_reach", lone_reach, "m",
      "Lanelet2 export: reach from a light or sign without stop line to its lanelet", in(1, 200));
    v("lanelet_max_curvature", max_curvature, "1/m",
      "Lanelet2 export: lane-line vertices bending sharper than this (kinks of the aggregated "
      "line; Lanelet2's validator warns above 0.5) are dropped from lanelet bounds",
      in(0.01, 10));
    v("lanelet_join_gap", join_gap, "m",
      "Lanelet2 export: two lane lines whose facing ends lie this close along the line (gap or "
      "overlap, at most 0.5 m across) are one line broken by aggregation: their ends are joined "
      "so that consecutive lanelets share their bounds' end nodes (0: no joins)",
      in(0, 10));
  }
};

}  // namespace mapfuse::lanelet
