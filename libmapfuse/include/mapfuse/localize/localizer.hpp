#pragma once
/// @file Localisation of a drive on a vector map (docs/localize.md; the experiment of Song et al.
/// 2023, §5 Fig. 12). Per keyframe: the observed elements of the keyframes within a travelled
/// window, placed by the drive's own relative poses, are matched to the map (lane / stop line
/// points point-to-line, poles / lights / planar centres point-to-point, within the class and the
/// lane-line attributes) and the planar pose (x, y, yaw) is solved in a small Ceres problem with a
/// Cauchy loss, the georeferenced (GPS) pose as a weak prior and the odometry prediction from the
/// previous localised keyframe; matching and solving alternate with a shrinking radius. A keyframe
/// with too few matches is lost; the next one re-acquires by a grid search around the prediction.
#include <cstdint>
#include <vector>

#include "mapfuse/core/classes.hpp"
#include "mapfuse/core/lsm.hpp"
#include "mapfuse/core/param.hpp"
#include "mapfuse/core/se3.hpp"
#include "mapfuse/localize/map_index.hpp"

namespace mapfuse::localize {

struct LocalizeSettings {
  double window = 12.0;              ///< m travelled either side: observations of these keyframes
  double window_sigma_per_m = 0.02;  ///< m/m, sigma added to a point per metre from keyframe k
  int rounds = 4;                    ///< matching + solve rounds per keyframe
  double match_radius = 1.5;         ///< m, matching radius of the first round
  double final_match_radius = 0.5;   ///< m, of the last round (linear in between)
  bool match_attributes = true;      ///< lane lines match only lines of their style and colour
  double line_sigma = 0.05;       ///< m, map line sigma, added to the observed point's covariance
  double point_sigma = 0.20;      ///< m, map point sigma (pole / light / planar centre), added too
  double robust_scale = 2.0;      ///< Cauchy scale, in sigmas
  double prior_sigma = 5.0;       ///< m, horizontal sigma of the georeferenced (GPS) prior
  double prior_sigma_yaw = 0.01;  ///< rad, its heading sigma
  double motion_sigma = 0.02;     ///< m, odometry noise added per prediction
  double motion_sigma_per_m = 0.03;       ///< m/m, its growth with the distance predicted
  double motion_sigma_yaw_per_m = 0.001;  ///< rad/m, heading noise added per metre predicted
  double search_radius = 4.0;      ///< m, half-width of the acquisition grid around the prediction
  double search_step = 0.5;        ///< m, its spacing
  int min_matches = 10;            ///< fewer matched points in the last round: the keyframe is lost
  int max_solver_iterations = 20;  ///< Ceres iterations per solve

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("window", window, "m", "observations of keyframes within this travelled distance join",
      in(0, 200));
    v("window_sigma_per_m", window_sigma_per_m, "m/m",
      "sigma added to a window point per metre between its keyframe and the localised one "
      "(relative poses of a georeferenced drive are not exact)",
      in(0, 10));
    v("rounds", rounds, "", "matching + solve rounds per keyframe", in(1, 50));
    v("match_radius", match_radius, "m", "matching radius of the first round", gt(0) & le(50));
    v("final_match_radius", final_match_radius, "m", "matching radius of the last round",
      gt(0) & le(50));
    v("match_attributes", match_attributes, "",
      "lane-line points match only map lines of the same style and colour");
    v("line_sigma", line_sigma, "m",
      "map line sigma, added to an observed point's own covariance across the line",
      gt(0) & le(100));
    v("point_sigma", point_sigma, "m",
      "map point sigma (pole / light / planar centre), added to the observed covariance",
      gt(0) & le(100));
    v("robust_scale", robust_scale, "sigma", "Cauchy loss scale", gt(0) & le(1000));
    v("prior_sigma", prior_sigma, "m", "horizontal sigma of the georeferenced (GPS) pose prior",
      gt(0) & le(1e6));
    v("prior_sigma_yaw", prior_sigma_yaw, "rad", "heading sigma of that prior", gt(0) & le(10));
    v("motion_sigma", motion_sigma, "m", "odometry noise added to each prediction",
      gt(0) & le(100));
    v("motion_sigma_per_m", motion_sigma_per_m, "m/m", "odometry noise added per metre predicted",
      in(0, 10));
    v("motion_sigma_yaw_per_m", motion_sigma_yaw_per_m, "rad/m",
      "heading noise added per metre predicted", gt(0) & le(10));
    v("search_radius", search_radius, "m", "half-width of the acquisition grid search", in(0, 100));
    v("search_step", search_step, "m", "spacing of the acquisition grid", gt(0.01) & le(100));
    v("min_matches", min_matches, "", "fewer matched points: the keyframe is lost", in(1, 100000));
    v("max_solver_iterations", max_solver_iterations, "", "Ceres iterations per solve",
      in(1, 1000));
    v.relation("final_match_radius", final_match_radius, final_match_radius <= match_radius,
               "<= match_radius");
    // the acquisition tries (2 search_radius / search_step + 1)^2 shifts
    v.relation("search_radius", search_radius, search_radius <= 100 * search_step,
               "<= 100 * search_step");
  }
};

/// When a localisation has lost the map (docs/localize.md "Lost map"): the share of lost
/// keyframes over all drives of a run.
struct LostMapSettings {
  double warn_lost_share = 0.05;  ///< above: a warning on stderr and in the summary
  double max_lost_share = 0.3;    ///< above: the run fails (exit 3), no output replaced

  template <class V>
  void visit(V& v) {
    v("warn_lost_share", warn_lost_share, "", "lost keyframes above this share: warning",
      param::in(0, 1));
    v("max_lost_share", max_lost_share, "", "lost keyframes above this share: the run fails",
      param::in(0, 1));
    v.relation("max_lost_share", max_lost_share, max_lost_share >= warn_lost_share,
               ">= warn_lost_share");
  }
};

/// One observed point, ready to match: its match key and position.
struct ObservedPoint {
  int key = 0;                                         ///< matchKey of its element
  bool is_line = false;                                ///< line point (else point / centre)
  Eigen::Vector3d p_body = Eigen::Vector3d::Zero();    ///< in its keyframe's body frame, m
  Eigen::Matrix3d cov_body = Eigen::Matrix3d::Zero();  ///< its covariance, body frame, m^2
};

/// What the localiser needs of a drive: per keyframe the prior pose and the observed points.
struct DriveObservations {
  std::vector<int64_t> ids;                        ///< keyframe ids
  std::vector<double> stamps;                      ///< s
  std::vector<Pose3> T_enu_body_prior;             ///< georeferenced (GPS) poses, ENU
  std::vector<std::vector<ObservedPoint>> points;  ///< per keyframe
};

/// @brief The observations of a georeferenced LSM: line elements point by point, poles and
/// lights by their base, planar elements by their centre, each under its anchor keyframe.
/// @throws InputError when the LSM is not in enu.
DriveObservations observationsOf(const Lsm& lsm, bool use_attributes, const std::string& source);

enum class KeyframeStatus : uint8_t { kOk, kLost };

struct KeyframeLocalization {
  int64_t id = 0;
  double stamp = 0.0;                     ///< s
  double distance = 0.0;                  ///< m travelled from the first keyframe (prior poses)
  Pose3 T_enu_body = Pose3::Identity();   ///< localised (lost: the odometry prediction)
  Pose3 T_enu_prior = Pose3::Identity();  ///< the georeferenced prior
  KeyframeStatus status = KeyframeStatus::kOk;
  int observed = 0;       ///< observed points in the window
  int matches = 0;        ///< matched in the last round
  double rms = 0.0;       ///< m, RMS distance of the matched points after the solve
  bool acquired = false;  ///< the acquisition search ran
};

struct LocalizeResult {
  std::vector<KeyframeLocalization> keyframes;
  int lost = 0;                ///< keyframes with status lost
  int acquisitions = 0;        ///< acquisition searches run
  long solver_iterations = 0;  ///< Ceres iterations, all solves
  double seconds = 0.0;        ///< wall time of the localisation

  double lostShare() const {
    return keyframes.empty() ? 1.0 : double(lost) / double(keyframes.size());
  }
};

/// @brief Localises every keyframe of `drive` on the map (docs/localize.md, eq. L1-L4).
/// @param map the map's index, in the same ENU frame as the drive's prior poses.
LocalizeResult localizeDrive(const MapIndex& map, const DriveObservations& drive,
                             const LocalizeSettings& settings);

const char* statusName(KeyframeStatus s);  ///< "ok", "lost"

}  // namespace mapfuse::localize
