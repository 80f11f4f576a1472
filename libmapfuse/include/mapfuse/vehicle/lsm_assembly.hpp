#pragma once
/// @file LSM assembly (Song et al. 2023 §3.3): ranged ground markings from consecutive frames
/// are merged per instance (by track id, or spatially when ids are absent), resampled along the
/// line, split into pieces anchored to the nearest keyframe (points in its body frame), and
/// written with per-point covariances; triangulated aerial elements are anchored likewise.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "mapfuse/core/lsm.hpp"
#include "mapfuse/core/param.hpp"

namespace mapfuse::vehicle {

/// One frame's ranged ground marking, already in the odom frame.
struct RangedMarking {
  CrowdClass cls = CrowdClass::kLaneLine;
  Attributes attributes;
  int64_t track_id = -1;
  int64_t truth_id = -1;
  int frame = 0;                             ///< index into the frame poses
  std::vector<Eigen::Vector3d> points;       ///< odom, m (ordered for lines, ring for planar)
  std::vector<Eigen::Matrix3d> covariances;  ///< odom, m^2
};

/// A triangulated aerial element in the odom frame.
struct AerialElement {
  CrowdClass cls = CrowdClass::kTrafficSign;
  int64_t truth_id = -1;
  std::vector<Eigen::Vector3d> points;       ///< odom: sign corners, or [base] for pole/light
  std::vector<Eigen::Matrix3d> covariances;  ///< odom, m^2
  double height = 0.0;                       ///< m, pole / light
  int observations = 1;
};

/// Settings of the assembly; the parameters declared once, in visit().
struct AssemblySettings {
  double association_radius = 0.6;   ///< m, spatial association of id-less markings
  double point_spacing = 0.5;        ///< m, resampling step along merged lines
  double max_element_length = 30.0;  ///< m, longer lines are split into anchored pieces
  double gap_split = 2.0;            ///< m, a gap this long along a line starts a new piece
  int min_observations = 2;          ///< frames needed to keep a ground instance
  double max_line_sigma = 0.5;  ///< m, less certain line samples beside a sounder line are ghosts
  double line_end_sigma_ratio = 2.5;  ///< far-view spill at a line's ends, × its sound quartile
  double area_sigma_ratio = 1.5;      ///< area outline from views this × its best quartile's sigma
  double keyframe_sigma_translation = 0.05;  ///< m, keyframe pose 1-sigma written to the LSM
  double keyframe_sigma_rotation = 0.002;    ///< rad

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("association_radius", association_radius, "m", "spatial merge radius of id-less markings",
      gt(0) & le(100));
    // the resampled lines hold length / point_spacing points
    v("point_spacing", point_spacing, "m", "resampling step along merged lines", in(0.01, 100));
    v("max_element_length", max_element_length, "m", "longer lines are split", gt(0) & le(10000));
    v.relation("max_element_length", max_element_length, max_element_length > point_spacing,
               "> point_spacing");
    v("line_gap_split", gap_split, "m", "a gap this long along a merged line starts a new piece",
      gt(0) & le(1000));
    v("min_observations", min_observations, "", "frames needed to keep a ground instance",
      in(1, 100000));
    // A stretch of line seen only from afar (no near view in its bins) carries eq. (1)'s far
    // errors: on esmini curves_elevation, samples above 0.8 m were 0.22-0.64 m RMS off their
    // lines, ghost lines beside the near views' one; below 0.5 m, 0.02-0.10 m.
    v("max_line_sigma", max_line_sigma, "m",
      "line samples whose horizontal 1-sigma (after covariance-weighted averaging) exceeds this "
      "and that lie within 2 m of a sounder sample of their class (a ghost beside the line seen "
      "near) are not mapped",
      gt(0) & le(1000));
    // Far views put a line's end (a dash's, a line's at a junction) 1-5 m beyond the paint, with
    // 2-8x the sigma of the near views (esmini curves_elevation: 0.15-0.5 m against 0.06 m,
    // 0.1-0.5 m aside on its R = 100 m curves), and the map's dashed line followed them across
    // every gap.
    v("line_end_sigma_ratio", line_end_sigma_ratio, "",
      "at each end of a line with a sound core, samples whose horizontal 1-sigma exceeds this "
      "multiple of the line's lower-quartile sigma are not mapped where the drive passed them "
      "(near views "
      "saw no paint there); beyond the drive's first or last frame they are kept",
      ge(1) & le(1000));
    // Where the views of a crosswalk or arrow disagree (partial mask views, oblique far views
    // while the drive turns), the outline is the hull of every view's points: the union of their
    // errors (seed 11 at 5 %: a 7 x 4 m crosswalk mapped 8.5 x 7.8 m by every drive; 4.7 x 7.2
    // m from the views within 1.5x, 7.1 x 8.4 m within 2.5x).
    v("area_sigma_ratio", area_sigma_ratio, "",
      "the outline of an area marking (crosswalk, arrow) is made from the views whose mean "
      "horizontal 1-sigma is at most this multiple of the lower quartile of its views' sigmas",
      ge(1) & le(1000));
    v("keyframe_sigma_translation", keyframe_sigma_translation, "m", "keyframe pose sigma",
      gt(0) & le(100));
    v("keyframe_sigma_rotation", keyframe_sigma_rotation, "rad", "keyframe pose sigma",
      gt(0) & le(10));
  }
};

struct AssemblyStats {
  int ground_instances = 0;      ///< merged instances before splitting
  int ground_dropped = 0;        ///< instances seen in too few frames
  int elements = 0;              ///< elements written
  int line_samples = 0;          ///< resampled line points before the sigma gate
  int line_samples_dropped = 0;  ///< of those, ghosts (above max_line_sigma, beside sound ones)
  int line_samples_spill = 0;    ///< of those, far-view spill past a line's end
};

/// @brief Builds the LSM. `frame_poses` are T_odom_body per frame, `keyframes` indices into
/// them, `stamps` per frame.
Lsm assembleLsm(const std::vector<Pose3>& frame_poses, const std::vector<double>& stamps,
                const std::vector<std::size_t>& keyframes,
                const std::vector<RangedMarking>& markings,
                const std::vector<AerialElement>& aerial, const AssemblySettings& settings,
                AssemblyStats* stats = nullptr);

}  // namespace mapfuse::vehicle
