#pragma once
/// @file Change detection of a map update (docs/update.md, issue 34): an existing vector map and
/// new drives' LSMs already in the map's ENU frame; per map element and new traversal the
/// expected observation area (was it in the camera's view at some keyframe), the evidence
/// (observed, observed elsewhere, observed with another type, missing), accumulated over the
/// traversals; clusters of observations no map element explains become additions.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "mapfuse/core/lsm.hpp"
#include "mapfuse/core/map_changes.hpp"
#include "mapfuse/core/param.hpp"
#include "mapfuse/core/vector_map.hpp"
#include "mapfuse/update/map_registration.hpp"

namespace mapfuse::update {

/// The camera footprint of a keyframe (docs/update.md "Expected observation area"). Defaults:
/// the simulated camera's (sim::CameraParams: x 1.8 m, ranges 4-40 m, 1280 px at fx 1000 px)
/// and the observer's lateral range 12 m, shrunk by `view_margin` so that an element at the edge
/// of the view, which a drive may or may not have kept, is no evidence either way.
struct ViewSettings {
  double camera_x = 1.8;          ///< m, camera ahead of the body origin
  double min_range = 4.0;         ///< m from the camera
  double max_range = 40.0;        ///< m from the camera
  double half_fov = 0.5696;       ///< rad, atan(640 / 1000)
  double lateral_range = 12.0;    ///< m, |y| in the body frame
  double view_margin = 1.0;       ///< m, the band is shrunk by this on every side
  double sample_spacing = 2.0;    ///< m between the samples of a lane line
  double pose_step = 1.0;         ///< m, poses interpolated between keyframes this far apart
  double coverage_radius = 6.0;  ///< m, the drive observed something this near (0: off)

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("view_camera_x", camera_x, "m", "camera position ahead of the body origin", in(-100, 100));
    v("view_min_range", min_range, "m", "nearest range of the camera view", in(0, 1000));
    v("view_max_range", max_range, "m", "farthest range of the camera view", gt(0) & le(1000));
    v.relation("view_max_range", max_range, max_range > min_range, "> view_min_range");
    v("view_half_fov", half_fov, "rad", "half the camera's horizontal field of view",
      gt(0) & le(1.6));
    v("view_lateral_range", lateral_range, "m", "max |y| (body) of observed elements",
      gt(0) & le(1000));
    v("view_margin", view_margin, "m", "the view is shrunk by this on every side", in(0, 100));
    v("sample_spacing", sample_spacing, "m", "spacing of the in-view samples of a lane line",
      in(0.1, 100));
    v("view_pose_step", pose_step, "m",
      "camera poses interpolated between keyframes this far apart", in(0.1, 1000));
    v("view_coverage_radius", coverage_radius, "m",
      "in view only where the drive observed something (any class) this near (0: off)",
      in(0, 1000));
  }
};

/// How one traversal's observations count as evidence about one map element.
struct EvidenceSettings {
  double min_confidence = 0.65;       ///< observations below are ignored (detector confidence)
  double match_distance = 1.0;        ///< m, a median displacement up to this is no move
  double move_max = 6.0;              ///< m, observations this close to an element are its evidence
  double restripe_min_shift = 0.2;    ///< m, median sideways offset of a shifted stretch
  double restripe_min_length = 10.0;  ///< m, shortest shifted stretch
  double line_search = 4.0;           ///< m, lane-line observations searched this far sideways
  double retype_margin = 0.3;         ///< m, a turned arrow fits this much better reflected

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("min_confidence", min_confidence, "", "observations of lower confidence are ignored",
      in(0, 1));
    v("match_distance", match_distance, "m", "a median displacement up to this is no move",
      gt(0) & le(100));
    v("move_max", move_max, "m", "observations this close to an element are its evidence",
      gt(0) & le(100));
    v.relation("move_max", move_max, move_max > match_distance, "> match_distance");
    v("restripe_min_shift", restripe_min_shift, "m",
      "median sideways offset of a re-striped stretch", gt(0) & le(100));
    v("restripe_min_length", restripe_min_length, "m", "shortest re-striped stretch",
      gt(0) & le(10000));
    v("line_search", line_search, "m", "lane-line observations searched this far sideways",
      gt(0) & le(100));
    v("retype_margin", retype_margin, "m", "a turned arrow fits this much better reflected",
      in(0, 100));
  }
};

/// How evidence accumulates over traversals (docs/update.md "Accumulation").
struct DecisionSettings {
  double detection_probability = 0.95;      ///< P(observed | present, in view), map without support
  double max_detection_probability = 0.99;  ///< the same from an element's support, at most
  double support_radius = 50.0;  ///< m, drives that passed an element: most support within this
  double false_alarm_probability = 0.02;  ///< P(observed | absent, in view)
  double removal_prior = 0.03;            ///< prior probability that an element was removed
  int added_min_traversals = 1;           ///< traversals that must see an addition
  double added_cluster_eps = 1.5;         ///< m, DBSCAN eps of the addition clusters

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("detection_probability", detection_probability, "",
      "probability that a drive observes an element it has in view, for a map without support "
      "counts",
      gt(0) & lt(1));
    v("max_detection_probability", max_detection_probability, "",
      "largest per-element detection probability from its support (the share of the drives "
      "that passed it and observed it)",
      gt(0) & lt(1));
    v("support_radius", support_radius, "m",
      "the drives that passed an element: the largest support of the map's elements this near",
      gt(0) & le(10000));
    v("false_alarm_probability", false_alarm_probability, "",
      "probability that a drive observes an absent element in view", gt(0) & lt(1));
    v.relation("detection_probability", detection_probability,
               detection_probability > false_alarm_probability, "> false_alarm_probability");
    v("removal_prior", removal_prior, "", "prior probability of a removal", gt(0) & lt(1));
    v("added_min_traversals", added_min_traversals, "", "traversals that must observe an addition",
      in(1, 100000));
    v("added_cluster_eps", added_cluster_eps, "m", "DBSCAN eps of addition clusters",
      gt(0) & le(100));
  }
};

struct UpdateSettings {
  RegistrationSettings registration;
  ViewSettings view;
  EvidenceSettings evidence;
  DecisionSettings decision;

  template <class V>
  void visit(V& v) {
    registration.visit(v);
    view.visit(v);
    evidence.visit(v);
    decision.visit(v);
  }
};

/// What the detection found besides the changes.
struct UpdateStats {
  int traversals = 0;
  int observations_used = 0;          ///< same-class observations of confidence >= min_confidence
  int elements_in_view = 0;           ///< map elements some traversal had in view
  std::vector<int64_t> not_verified;  ///< ids of map elements no traversal had in view
  int confirmed = 0;                  ///< elements in view and found unchanged
  int undecided = 0;                  ///< in view, evidence too weak for a change or a confirmation
  std::vector<StretchOffset> stretches;  ///< map-relative registration of the new drives
};

struct UpdateResult {
  MapChanges changes;  ///< mapfuse.map_changes, ids of `map`, confidence and traversals set
  UpdateStats stats;
  std::vector<Lsm> registered;  ///< the new drives as registered to the map (keyframes moved)
};

/// @brief Detects the changes between `map` and the new drives.
/// The new drives are first registered to the map (registerToMap, unless disabled).
/// @param lsms new drives in frame enu with the map's origin; `sources[i]` names lsms[i].
/// @throws InputError when an LSM is not in frame enu or its origin differs from the map's.
UpdateResult detectChanges(const VectorMap& map, const std::vector<Lsm>& lsms,
                           const std::vector<std::string>& sources, const UpdateSettings& settings);

}  // namespace mapfuse::update
