#pragma once
/// @file The map's own frame (docs/localize.md "Evaluation frames"): a map is a frame of its own,
/// and a vehicle localised on it is localised in that frame. The rigid planar transform that
/// carries a map onto the truth map (rotation about z and a shift), estimated from the two maps
/// alone: the map's line vertices (every `sample_step` m) and element points matched to the
/// truth map's targets of their class, point-to-line / point-to-point with a Cauchy loss, with
/// the radius shrinking as in the localiser (eq. L1-L2, L4 without priors). The truth carried
/// into the map's frame by it gives the localisation's error relative to the map.
#include "mapfuse/core/se3.hpp"
#include "mapfuse/core/vector_map.hpp"
#include "mapfuse/localize/localizer.hpp"
#include "mapfuse/localize/map_index.hpp"

namespace mapfuse::localize {

struct MapToTruth {
  Pose3 T_truth_map = Pose3::Identity();  ///< truth ENU <- map ENU (planar: z rotation, shift)
  double dx = 0.0, dy = 0.0;              ///< m, the shift of the map's centroid (ENU)
  double yaw_deg = 0.0;                   ///< deg, the rotation about the centroid
  int points = 0;                         ///< map sample points
  int matched = 0;                        ///< of them matched within final_match_radius
  double rms_before = 0.0;                ///< m, RMS distance of the matched points, as is
  double rms_after = 0.0;                 ///< m, after the transform
};

/// @brief Estimates the rigid planar transform from `map` to the truth (both in one ENU frame)
/// with the localiser's matching settings (match_radius -> final_match_radius over `rounds`,
/// line_sigma, point_sigma, robust_scale, match_attributes of `truth`).
/// @throws InputError when fewer than 3 map points match the truth (no common ground).
MapToTruth estimateMapToTruth(const VectorMap& map, const MapIndex& truth,
                              const LocalizeSettings& settings, double sample_step = 1.0);

}  // namespace mapfuse::localize
