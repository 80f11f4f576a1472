#pragma once
/// @file What one new traversal says about one map element (docs/update.md "Evidence").
#include <Eigen/Core>
#include <cstdint>
#include <utility>
#include <vector>

#include "mapfuse/aggregate/observations.hpp"
#include "mapfuse/core/vector_map.hpp"
#include "mapfuse/update/change_detection.hpp"

namespace mapfuse::update {

class DriveView;
class SegmentIndex;

/// One traversal's evidence about one element it had in view.
struct Evidence {
  int drive = 0;
  bool present = false;                                    ///< observed here or displaced
  Eigen::Vector2d displacement = Eigen::Vector2d::Zero();  ///< observed minus mapped centre
  bool other_type = false;                                 ///< dashed <-> solid, or an arrow turned
  bool shifted = false;                     ///< lane line: a stretch shifted sideways
  double shift = 0.0;                       ///< m, median offset of that stretch (left +)
  double shift_from = 0.0, shift_to = 0.0;  ///< m along the line, the stretch
  /// lane line: per in-view sample with an observed line beside it (index of the line's samples
  /// every sample_spacing m), the signed sideways offset of that line (left +), m
  std::vector<std::pair<int, double>> offsets;
};

/// The observations of one drive, one class, confident enough.
using DriveObservations = std::vector<const aggregate::Observation*>;

/// @brief A point or planar element's evidence from the observations assigned to it (those of
/// the drive whose nearest element of the class it is, within move_max): present when any,
/// displaced by the nearest one; an arrow whose polygon fits better turned round is retyped.
Evidence discreteEvidence(const MapInstance& element, const DriveObservations& assigned, int drive,
                          const EvidenceSettings& s);

/// @brief A lane line's evidence: samples in view with an observed line beside them (offset,
/// style); a sideways-shifted stretch of at least restripe_min_length; the style most samples
/// see. `has_data` false when no in-view sample had an observation (no evidence). An observation
/// nearer to one of `neighbours` (the map's other lane lines near this one) than to this line is
/// theirs, not evidence about this one.
Evidence laneLineEvidence(const MapInstance& line,
                          const std::vector<const MapInstance*>& neighbours,
                          const SegmentIndex& lines, const DriveView& view, int drive,
                          const UpdateSettings& s, bool* in_view, bool* has_data);

/// @brief Centre of an observation, as instanceCentre of an element of its geometry.
Eigen::Vector3d observationCentre(const aggregate::Observation& o);

/// @brief Horizontal distance used to assign an observation to an element: centre to centre,
/// or for a stop line the observed centre to the mapped segment (a partly seen stop line).
double assignmentDistance(const MapInstance& element, const aggregate::Observation& o);

/// @brief The element's polygon or point turned round its extent centre (a reversed arrow).
std::vector<Eigen::Vector3d> turnedRound(const std::vector<Eigen::Vector3d>& points);

}  // namespace mapfuse::update
