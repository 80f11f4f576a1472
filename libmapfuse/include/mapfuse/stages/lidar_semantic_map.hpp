#pragma once
/// @file Stage `lidar-semantic-map` (Jeong et al. 2018; docs/lidar.md): KITTI raw drive ->
/// semantic voxel map (PLY, PCD), per-scan SemanticKITTI labels, top-down PNG, summary; and
/// `train`, which fits the per-label cluster classifiers from labelled drives.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mapfuse/cli/params.hpp"

namespace mapfuse::stages {

struct LidarSemanticMapParams {
  // frames
  int first_frame = 0;  ///< first frame index
  int last_frame = -1;  ///< last frame index (inclusive), -1 = all
  int stride = 1;       ///< every stride-th frame present
  // poses
  std::string pose_source = "auto";  ///< auto | oxts | oxts_enu | poses_file | odometry
  std::string poses_file;        ///< KITTI poses file, T_world_cam0 (docs/kitti.md, "Poses files")
  double odom_voxel_size = 1.0;  ///< m, local-map voxel (docs/lidar.md, "Odometry")
  bool odom_deskew = true;
  bool odom_exclude_road_users = false;
  int odom_max_untrusted = 0;  ///< untrusted odometry steps tolerated; one more: exit 3
  // semantics
  std::string segmenter = "auto";  ///< auto | enet | precomputed
  std::string model;  ///< ENet model; empty = <shared>/models/enet-cityscapes/enet-model.net
  double enet_scale = 1.0;
  std::string semantics_dir;    ///< precomputed folder; empty = <drive>/semantics_02
  bool cache_semantics = true;  ///< ENet outputs cached in <output>/semantics_02
  double label_confidence = 0.7;
  double min_probability = 0.02;
  // projection and map
  double min_range = 5.0;    ///< m
  double max_range = 50.0;   ///< m
  double voxel_size = 0.05;  ///< m
  double min_log_prob = -20.0;
  // error minimisation
  std::string classifier_dir;      ///< rtrees_<label>.yml folder; empty = step skipped
  double cluster_tolerance = 0.5;  ///< m
  int cluster_min_points = 5;
  int rtrees_max_depth = 12;
  int rtrees_trees = 100;
  int rtrees_min_samples = 5;
  uint64_t seed = 42;
  // refinement
  bool refine = true;
  int knn_k = 6;
  double knn_max_mean_distance = 0.20;  ///< m
  bool remove_vehicle_traces = true;
  double trace_eps = 0.25;  ///< m
  int trace_min_points = 5;
  int trace_max_voxels = 100000;     ///< paper: 500, for its coarser voxels (docs/lidar.md)
  double trace_max_length = 10.0;    ///< m
  bool trace_seen_through = true;    ///< drop voxels that other scans see through
  double seen_through_margin = 0.5;  ///< m
  int seen_through_window = 0;       ///< pixels (half size)
  int seen_through_window_thin = 1;  ///< pixels, road / sidewalk / fence / pole / vegetation
  int seen_through_min_scans = 1;
  double seen_through_min_ratio = 0.5;
  double seen_through_vote_radius = 0.5;  ///< m, vehicle voxels' neighbourhood vote; 0: off
  double seen_through_vote_share = 0.6;
  // outputs
  double topdown_resolution = 0.1;  ///< m/px
  bool write_scan_labels = true;
  int num_threads = 1;

  template <class V>
  void visit(V& v) {
    v("first_frame", first_frame, "", "first frame index");
    v("last_frame", last_frame, "", "last frame index, inclusive (-1 = all)");
    v("stride", stride, "", "use every stride-th frame present");
    v("pose_source", pose_source, "",
      "auto|oxts|oxts_enu|poses_file|odometry (auto: OXTS when every frame has it, else the poses "
      "file if given or the sequence's poses.txt, else odometry)");
    v("poses_file", poses_file, "",
      "KITTI poses file, T_world_cam0 (line i = frame i, or one line per selected frame; "
      "docs/kitti.md)");
    v("odom_voxel_size", odom_voxel_size, "m",
      "odometry local-map voxel (its nearest-neighbour reach; docs/lidar.md)");
    v("odom_deskew", odom_deskew, "", "constant-velocity de-skew of each sweep");
    v("odom_exclude_road_users", odom_exclude_road_users, "",
      "leave low objects (road users) out of the odometry (geometric rule, docs/lidar.md; off: "
      "measured no better, and it drops nearby walls)");
    v("odom_max_untrusted", odom_max_untrusted, "",
      "untrusted odometry steps tolerated (listed in the summary); one more stops the run, exit 3");
    v("segmenter", segmenter, "",
      "auto|enet|precomputed (auto: precomputed when the folder has the first frame)");
    v("model", model, "",
      "ENet Torch7 model (empty = <shared>/models/enet-cityscapes/enet-model.net)");
    v("enet_scale", enet_scale, "", "ENet input scale (1.0 native, 1.5 also fine)");
    v("semantics_dir", semantics_dir, "",
      "precomputed semantics folder (empty = <drive>/semantics_02)");
    v("cache_semantics", cache_semantics, "", "cache ENet outputs in <output>/semantics_02");
    v("label_confidence", label_confidence, "", "probability given to the label of a label image");
    v("min_probability", min_probability, "", "floor of every class probability of a measurement");
    v("min_range", min_range, "m", "nearest point used for labelling");
    v("max_range", max_range, "m", "farthest point used for labelling");
    v("voxel_size", voxel_size, "m", "voxel edge");
    v("min_log_prob", min_log_prob, "", "floor of a voxel's class log posterior (nats)");
    v("classifier_dir", classifier_dir, "",
      "folder of rtrees_<label>.yml (empty = error minimisation skipped)");
    v("cluster_tolerance", cluster_tolerance, "m", "Euclidean clustering gap");
    v("cluster_min_points", cluster_min_points, "", "smallest cluster judged by a forest");
    v("rtrees_max_depth", rtrees_max_depth, "", "train: tree depth");
    v("rtrees_trees", rtrees_trees, "", "train: trees per forest");
    v("rtrees_min_samples", rtrees_min_samples, "",
      "train: correct and wrong clusters a label needs");
    v("seed", seed, "", "train: random seed");
    v("refine", refine, "", "run the batch refinement");
    v("knn_k", knn_k, "", "K of the K-nearest-voxel filter");
    v("knn_max_mean_distance", knn_max_mean_distance, "m", "delta_d of the K-nearest-voxel filter");
    v("remove_vehicle_traces", remove_vehicle_traces, "", "remove moving-vehicle traces");
    v("trace_eps", trace_eps, "m", "DBSCAN radius on the 2D vehicle projection");
    v("trace_min_points", trace_min_points, "", "DBSCAN minimum points (2D cells)");
    v("trace_max_voxels", trace_max_voxels, "",
      "eta_d: clusters with more vehicle voxels are traces");
    v("trace_max_length", trace_max_length, "m", "eta_l: clusters longer than this are traces");
    v("trace_seen_through", trace_seen_through, "",
      "also drop voxels that other scans see through (free-space test)");
    v("seen_through_margin", seen_through_margin, "m",
      "a return this far beyond a voxel means the ray passed it");
    v("seen_through_window", seen_through_window, "px",
      "half size of the range-image window whose nearest return must lie beyond");
    v("seen_through_window_thin", seen_through_window_thin, "px",
      "the same for road, sidewalk, fence, pole and vegetation voxels");
    v("seen_through_min_scans", seen_through_min_scans, "",
      "scans that must see through a voxel before it goes");
    v("seen_through_min_ratio", seen_through_min_ratio, "",
      "and their share among the scans that saw the voxel");
    v("seen_through_vote_radius", seen_through_vote_radius, "m",
      "vehicle voxels go by the vote of the vehicle voxels within this (x, y) radius; 0: each "
      "alone");
    v("seen_through_vote_share", seen_through_vote_share, "",
      "share of seen-through vehicle voxels in that neighbourhood that removes them");
    v("topdown_resolution", topdown_resolution, "m", "top-down PNG pixel size");
    v("write_scan_labels", write_scan_labels, "",
      "write labels/<frame>.label for every input scan");
    v("num_threads", num_threads, "", "OpenMP threads");
  }
  /// @throws ConfigError naming field, value and rule.
  void validate() const;
};

/// @brief Builds the semantic voxel map of one drive into `output` (map.ply, map.pcd,
/// labels/<frame>.label, topdown.png, poses.txt, lidar-semantic-map.{config,summary}.json).
/// @return the summary written.
nlohmann::json runLidarSemanticMap(const std::filesystem::path& drive,
                                   const std::filesystem::path& output,
                                   const LidarSemanticMapParams& params);

/// @brief Fits the per-label RTrees from drives that carry labels/<frame>.label files; writes
/// rtrees_<label>.yml and lidar-semantic-map-train.{config,summary}.json into `output`.
nlohmann::json runLidarSemanticMapTrain(const std::vector<std::filesystem::path>& drives,
                                        const std::filesystem::path& output,
                                        const LidarSemanticMapParams& params);

}  // namespace mapfuse::stages
