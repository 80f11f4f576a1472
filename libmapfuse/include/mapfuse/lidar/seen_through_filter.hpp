#pragma once
/// @file Free-space test for the map's voxels: a voxel that other scans see through — their rays
/// pass it and return from something farther away — was occupied only for a while, the trace of
/// a moving vehicle; a parked vehicle stops the rays of every scan that looks at it. Each scan
/// becomes a spherical range image; a voxel is "seen through" by the scan when the nearest return
/// in the pixel window around its direction lies more than `margin` beyond it. Every class is
/// tested, since the camera labels part of a moving car as road, building, ...; ground, fence,
/// pole and vegetation voxels (grazed by rays, or thin, or porous) use the wider `window_thin`.
/// The range-image visibility idea follows Kim & Kim, "Remove, then Revert" (IROS 2020); it
/// complements the paper's size rules (eta_d, eta_l; Jeong et al. 2018, §2.2), which cannot tell
/// a trace shorter than eta_l from a parked car.
///
/// Vehicle voxels are then decided by neighbourhood vote: a vehicle voxel goes when at least
/// `vehicle_vote_share` of the vehicle voxels within `vehicle_vote_radius` of it in (x, y), at any
/// height, were seen through. A trace's lowest layer (rays to it return from the road just behind,
/// within the margin) and the voxels no later scan had a clear view of go with the seen-through
/// body above and around them; the odd voxel at a parked car's edge that a grazing ray passed stays
/// with the car.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "mapfuse/core/param.hpp"
#include "mapfuse/core/se3.hpp"
#include "mapfuse/lidar/voxel_map.hpp"

namespace mapfuse::lidar {

struct SeenThroughSettings {
  double azimuth_resolution_deg = 0.2;    ///< range-image column width (HDL-64E: ~0.17 deg)
  double elevation_resolution_deg = 0.5;  ///< range-image row height (HDL-64E: ~0.4 deg)
  double elevation_min_deg = -26.0;       ///< lowest beam covered
  double elevation_max_deg = 4.0;         ///< highest beam covered
  int window = 0;            ///< half size of the pixel window whose nearest return must lie beyond
  int window_thin = 1;       ///< the same for road, sidewalk, fence, pole and vegetation voxels
  double margin = 0.5;       ///< m, a return this far beyond the voxel means the ray passed it
  int min_seen_through = 1;  ///< scans that must see through a voxel before it goes
  double min_free_ratio = 0.5;       ///< and their share among the scans that saw it at all
  double vehicle_vote_radius = 0.5;  ///< m, (x, y) neighbourhood of the vehicle vote; 0: per voxel
  double vehicle_vote_share = 0.6;   ///< share of seen-through vehicle voxels that removes them all

  /// The parameters of lidar-semantic-map (the ranges and the thread count are the run's:
  /// SeenThroughFilter's arguments).
  template <class V>
  void visit(V& v) {
    using namespace param;
    v("seen_through_azimuth_resolution", azimuth_resolution_deg, "deg",
      "range-image column width of the free-space test (HDL-64E: ~0.17)", gt(0.01) & le(10));
    v("seen_through_elevation_resolution", elevation_resolution_deg, "deg",
      "range-image row height of the free-space test (HDL-64E: ~0.4)", gt(0.01) & le(10));
    v("seen_through_elevation_min", elevation_min_deg, "deg",
      "lowest beam elevation the range image covers", in(-90, 90));
    v("seen_through_elevation_max", elevation_max_deg, "deg",
      "highest beam elevation the range image covers", in(-90, 90));
    v.relation("seen_through_elevation_max", elevation_max_deg,
               elevation_max_deg > elevation_min_deg, "> seen_through_elevation_min");
    v("seen_through_margin", margin, "m",
      "a return this far beyond a voxel means the ray passed it", gt(0) & le(100));
    v("seen_through_window", window, "px",
      "half size of the range-image window whose nearest return must lie beyond", in(0, 5));
    v("seen_through_window_thin", window_thin, "px",
      "the same for road, sidewalk, fence, pole and vegetation voxels", in(0, 5));
    v("seen_through_min_scans", min_seen_through, "",
      "scans that must see through a voxel before it goes", in(1, 65535));
    v("seen_through_min_ratio", min_free_ratio, "",
      "and their share among the scans that saw the voxel", in(0, 1));
    v("seen_through_vote_radius", vehicle_vote_radius, "m",
      "vehicle voxels go by the vote of the vehicle voxels within this (x, y) radius; 0: each "
      "alone",
      in(0, 5));
    v("seen_through_vote_share", vehicle_vote_share, "",
      "share of seen-through vehicle voxels in that neighbourhood that removes them",
      gt(0) & le(1));
  }
};

/// The sensor's reach over which voxels are tested: voxels nearer than min_range or farther than
/// max_range from the sensor are not (lidar-semantic-map passes its projection's ranges).
struct SensorReach {
  double min_range = 2.0;   ///< m
  double max_range = 50.0;  ///< m (sparse returns beyond)
};

struct SeenThroughStats {
  std::size_t tested_voxels = 0;   ///< voxels of the map
  std::size_t scans = 0;           ///< scans added
  std::size_t removed_voxels = 0;  ///< voxels dropped by keepMask()
};

/// Accumulates, scan by scan, how often each voxel of a map was seen through or hit. Voxels are
/// grouped in 10 m (x, y) columns so that a scan tests only those within max_range of it.
class SeenThroughFilter {
 public:
  /// @param map the map to test; it must outlive the filter and stay unchanged while in use
  /// @throws InputError on a non-positive resolution, margin, range or window < 0.
  /// @param num_threads OpenMP threads of addScan (results do not depend on it)
  SeenThroughFilter(const SemanticVoxelMap& map, const SeenThroughSettings& s,
                    const SensorReach& reach = {}, int num_threads = 1);

  /// @brief Tests every voxel against one scan.
  /// @param scan_velo the scan's points in the sensor frame
  /// @param T_map_velo pose of the sensor in the map
  void addScan(const std::vector<Eigen::Vector3f>& scan_velo, const Pose3& T_map_velo);

  /// @brief Keep mask over the map's voxels: 0 for voxels seen through by at least
  /// min_seen_through scans and by at least min_free_ratio of the scans that saw them; vehicle
  /// voxels by the vote of their neighbourhood (see the file comment).
  std::vector<uint8_t> keepMask(SeenThroughStats* stats) const;

 private:
  SeenThroughSettings s_;
  SensorReach reach_;
  int num_threads_ = 1;
  const SemanticVoxelMap* map_;          ///< tested map (must outlive the filter)
  std::vector<uint16_t> through_, hit_;  ///< per voxel: scans that saw through / stopped at it
  struct Column {
    uint64_t key;         ///< packed (x, y) cell
    uint32_t begin, end;  ///< range of order_
  };
  std::vector<Column> columns_;  ///< sorted by key
  std::vector<uint32_t> order_;  ///< voxel indices grouped by column
  static uint64_t columnKey(const Eigen::Vector3d& p);
  /// Replaces the vehicle voxels' own verdicts in `keep` by their neighbourhood's vote.
  void voteOverVehicles(std::vector<uint8_t>& keep) const;
  std::vector<float> image_;  ///< range image, reused across scans
  int cols_ = 0, rows_ = 0;
  std::size_t scans_ = 0;
};

}  // namespace mapfuse::lidar
