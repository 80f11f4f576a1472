#pragma once
/// @file Content checks of a parsed OpenDRIVE map (docs/formats.md "Map content checks"): what
/// the XML syntax cannot say. Structural nonsense is refused (ParseError naming file, road and
/// record: a curve collapsed to a point, a lane width beyond any road); what can still be used is
/// repaired with a warning per kind in map.warnings (a road length that disagrees with its plan
/// view, a zero-length record, a negative lane width, links to missing roads); what cannot be
/// placed is dropped with a warning (a road whose plan view has a gap, a lane section, signal or
/// object beyond its road's end).
#include "mapfuse/io/opendrive.hpp"

namespace mapfuse::sim {

/// Tolerances and bounds of the checks (documented in docs/formats.md).
struct OdrCheckLimits {
  double join = 0.01;            ///< m: plan-view records meeting closer are continuous
  double max_gap = 1.0;          ///< m: a larger gap between records drops the road
  double length_slack = 0.01;    ///< m: road length vs plan-view end before a warning
  double beyond_end = 1.0;       ///< m: signals / objects / sections farther past the end dropped
  double max_lane_width = 50.0;  ///< m: a wider lane is refused
  double negative_width = 0.01;  ///< m: widths below -this are warned (taken as 0)
  double min_curve_ratio = 0.5;  ///< a record's drawn length / stated length below: refused
  double max_curve_ratio = 2.0;  ///< ... above (plus 1 m): refused
};

/// @brief Checks and repairs `map` in place (warnings into map.warnings).
/// @throws ParseError for structural nonsense; InputError when no road is left.
void checkOpenDriveContent(io::OdrMap& map, const OdrCheckLimits& limits = {});

}  // namespace mapfuse::sim
