#pragma once
/// @file What a vehicle would upload (docs/simulate.md "LSM level"): keyframes of the drifting
/// odometry every few metres; per keyframe the true elements in camera range and field of view
/// of its stretch of road, in the keyframe's body frame, with range-dependent noise and
/// per-point covariance, missed detections and false positives (truth_id -1); dashed lines one
/// element per dash; GPS fixes.
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "mapfuse/core/lsm.hpp"
#include "mapfuse/core/param.hpp"
#include "mapfuse/sim/drive.hpp"
#include "mapfuse/sim/point_cells.hpp"
#include "mapfuse/sim/sim_camera.hpp"
#include "mapfuse/sim/world.hpp"

namespace mapfuse::sim {

struct ObservationParams {
  double keyframe_spacing = 8.0;      ///< m of odometry between keyframes
  double point_spacing = 0.75;        ///< m between lane-line points
  double lateral_range = 12.0;        ///< m, |y| limit of observed elements (body)
  double aerial_window_offset = 6.0;  ///< m, aerial elements are assigned further ahead
  /// Ground points beside the road, outside the image at x_near, are observed farther ahead,
  /// where the field of view first holds them with this many pixels to spare at the image edge
  /// (0 = off: the fixed window [x_near, x_near + spacing) for every lateral offset).
  double ground_edge_margin_px = 40.0;
  double ground_sigma_base = 0.03;        ///< m, ground point noise floor
  double ground_sigma_range_quad = 3e-4;  ///< 1/m, along-ray sigma grows as k r^2 (eq. 1)
  double ground_sigma_angular = 0.002;    ///< rad, across-ray sigma grows as k r
  double aerial_sigma_base = 0.10;        ///< m, triangulated point noise floor
  double aerial_sigma_range_quad = 5e-4;  ///< 1/m, depth sigma grows as k r^2
  double correlated_fraction = 0.5;       ///< share of the noise variance common to an element
  double miss_probability = 0.05;         ///< per element and keyframe
  double false_positives_per_km = 5.0;    ///< spurious elements per km driven
  /// m; a stop line whose centre a drive never sees is observed once, its longest visible run,
  /// when that is at least this long (0: off, only whole stop lines are observed)
  double partial_stop_line_min_length = 1.0;

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("keyframe_spacing", keyframe_spacing, "m", "odometry distance between keyframes",
      in(1, 10000));
    v("point_spacing", point_spacing, "m", "lane-line point spacing in LSMs", in(0.1, 100));
    // the observer looks up true elements within about lateral_range of each keyframe
    v("lateral_range", lateral_range, "m", "max |y| of observed elements", gt(0) & le(1000));
    v("aerial_window_offset", aerial_window_offset, "m",
      "aerial elements are anchored this much further ahead", in(-1000, 1000));
    v("ground_edge_margin_px", ground_edge_margin_px, "px",
      "ground points beside the road are observed where the image first holds them with this "
      "margin (0: fixed window at camera_min_range)",
      in(0, 10000));
    v("ground_sigma_base", ground_sigma_base, "m", "ground point noise floor", in(0, 100));
    v("ground_sigma_range_quad", ground_sigma_range_quad, "1/m", "along-ray ground sigma k r^2",
      in(0, 1));
    v("ground_sigma_angular", ground_sigma_angular, "rad", "across-ray sigma k r", in(0, 1));
    v("aerial_sigma_base", aerial_sigma_base, "m", "triangulated point noise floor", in(0, 100));
    v("aerial_sigma_range_quad", aerial_sigma_range_quad, "1/m", "aerial depth sigma k r^2",
      in(0, 1));
    v("correlated_fraction", correlated_fraction, "",
      "share of noise variance common to an element", in(0, 1));
    v("miss_probability", miss_probability, "", "missed detection probability per element",
      in(0, 1) & lt(1));
    v("partial_stop_line_min_length", partial_stop_line_min_length, "m",
      "a stop line whose centre a drive never sees: its visible part at least this long is "
      "observed (0 = off)",
      in(0, 1000));
    v("false_positives_per_km", false_positives_per_km, "1/km", "spurious elements per km",
      in(0, 1e6));
  }
};

/// The true elements cut into observable pieces, with a grid index.
class PieceIndex {
 public:
  PieceIndex(const World& world, double point_spacing);
  struct Piece {
    std::size_t instance;  ///< index into World::truth.instances
    Polyline points;       ///< ENU
    Eigen::Vector3d centroid;
  };
  const std::vector<Piece>& pieces() const { return pieces_; }
  /// @brief Indices of pieces with a point within about `radius` m of `center` (xy).
  std::vector<int> near(const Eigen::Vector3d& center, double radius) const;
  /// @brief Indices, ascending, of piece `pi`'s points in the cells near() visits for the same
  /// query; every index of a short piece. A solid lane line is one piece however long: a
  /// keyframe visits the points near it, not all of them (a 20 km road: O(keyframes x points)).
  std::vector<uint32_t> pointsNear(int pi, const Eigen::Vector3d& center, double radius) const;

 private:
  double cell_ = 10.0;
  std::vector<Piece> pieces_;
  std::unordered_map<int64_t, std::vector<int>> grid_;
  /// Per piece: its points by cell (empty for a piece of fewer than kIndexedPoints points).
  std::vector<PointCells> point_cells_;
};

/// Counts of one observed traversal.
struct ObservationStats {
  int elements = 0;  ///< true observations written
  int false_positives = 0;
  int missed = 0;
  int partial_stop_lines = 0;  ///< stop lines observed only in part (their centre never seen)
};

struct ObservedDrive {
  Lsm lsm;
  std::vector<std::size_t> keyframe_samples;  ///< Drive sample index of each keyframe
  ObservationStats stats;
};

/// @brief Keyframe samples: camera instants at least `spacing` m of odometry apart (first and
/// last included).
std::vector<std::size_t> selectKeyframeSamples(const Drive& drive, double camera_rate,
                                               double imu_rate, double spacing);

/// @brief Builds the LSM of one drive. @param seed this drive's observation seed.
ObservedDrive observeLsm(const World& world, const PieceIndex& index, const Drive& drive,
                         const SimCamera& camera, const ObservationParams& params,
                         const DriveParams& drive_params, uint64_t seed);

}  // namespace mapfuse::sim
