#include "mapfuse/stages/lidar_semantic_map.hpp"

#include <chrono>
#include <set>

#include "mapfuse/core/classes.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/core/progress.hpp"
#include "mapfuse/io/kitti_poses.hpp"
#include "mapfuse/io/output_transaction.hpp"
#include "mapfuse/io/pcd.hpp"
#include "mapfuse/io/picture_key.hpp"
#include "mapfuse/io/ply.hpp"
#include "mapfuse/io/png_frames.hpp"
#include "mapfuse/io/semantic_kitti.hpp"
#include "mapfuse/io/stage_report.hpp"
#include "mapfuse/io/velodyne.hpp"
#include "mapfuse/lidar/drive_odometry.hpp"
#include "mapfuse/lidar/drive_poses.hpp"
#include "mapfuse/lidar/map_export.hpp"
#include "mapfuse/lidar/refinement.hpp"
#include "mapfuse/lidar/seen_through_filter.hpp"
#include "mapfuse/stages/lidar_semantic_map_detail.hpp"

namespace mapfuse::stages {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {
constexpr const char* kStage = "lidar-semantic-map";
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

/// Poses of the selected frames in the map frame (first selected frame at the origin).
std::vector<Pose3> drivePoses(const io::KittiRawDrive& drive, const LidarSemanticMapParams& p,
                              json& report) {
  std::string src = p.pose_source;
  if (src == "auto")
    src = (drive.has_oxts && drive.calib.has_imu)              ? "oxts"
          : !p.poses_file.empty() || !drive.poses_file.empty() ? "poses_file"
                                                               : "odometry";
  report["source"] = src;
  std::vector<Pose3> poses;
  if (src == "oxts" || src == "oxts_enu") {
    if (!drive.has_oxts) throw InputError(drive.dir.string() + ": not every frame has OXTS");
    poses = lidar::oxtsVeloPoses(drive, src == "oxts_enu");
    const Eigen::Vector3d t0 = lidar::recenter(poses);
    report["origin_translation"] = {t0.x(), t0.y(), t0.z()};
    const auto ox = io::readOxts(drive.frames.front());
    report["origin_wgs84"] = {{"lat", ox.lat}, {"lon", ox.lon}, {"alt", ox.alt}};
  } else if (src == "poses_file") {
    const fs::path file = !p.poses_file.empty() ? fs::path(p.poses_file) : drive.poses_file;
    if (file.empty())
      throw ConfigError("pose_source poses_file needs --poses-file (or a sequence's poses.txt)");
    report["file"] = file.string();
    poses = lidar::veloPosesFromFile(drive, file);
  } else if (src == "odometry") {
    lidar::DriveOdometrySettings os;
    os.odometry.voxel_size = p.odom_voxel_size;
    os.odometry.deskew = p.odom_deskew;
    os.odometry.exclude_road_users = p.odom_exclude_road_users;
    os.max_untrusted = p.odom_max_untrusted;
    const lidar::DriveOdometryResult odo = lidar::runDriveOdometry(drive, os);
    poses = odo.T_odom_velo;
    report.update(lidar::odometryReport(odo, os));
  } else {
    throw ConfigError("pose_source = \"" + src +
                      "\". Violated constraint: one of auto, oxts, oxts_enu, poses_file, odometry");
  }
  return poses;
}
}  // namespace

void LidarSemanticMapParams::validate() const {
  const char* s = "LidarSemanticMapParams";
  requireParam(first_frame >= 0 && first_frame <= 1000000000, s, "first_frame", first_frame,
               "in [0, 1e9]");
  requireParam(last_frame < 0 || last_frame >= first_frame, s, "last_frame", last_frame,
               "-1 or >= first_frame");
  requireParam(stride >= 1 && stride <= 1000000, s, "stride", stride, "in [1, 1e6]");
  requireParam(odom_voxel_size >= 0.01 && odom_voxel_size <= 10, s, "odom_voxel_size",
               odom_voxel_size, "in [0.01, 10]");
  requireParam(odom_max_untrusted >= 0 && odom_max_untrusted <= 1000000000, s,
               "odom_max_untrusted", odom_max_untrusted, "in [0, 1e9]");
  requireParam(enet_scale > 0.1 && enet_scale <= 4, s, "enet_scale", enet_scale, "in (0.1, 4]");
  requireParam(label_confidence > 1.0 / kNumLidarClasses && label_confidence <= 1, s,
               "label_confidence", label_confidence, "in (1/8, 1]");
  requireParam(min_probability > 0 && min_probability < 1.0 / kNumLidarClasses, s,
               "min_probability", min_probability, "in (0, 1/8)");
  requireParam(min_range >= 0 && min_range <= 1000, s, "min_range", min_range, "in [0, 1000]");
  requireParam(max_range > min_range && max_range <= 1000, s, "max_range", max_range,
               "> min_range, <= 1000");
  requireParam(voxel_size >= 0.005 && voxel_size <= 10, s, "voxel_size", voxel_size,
               "in [0.005, 10]");
  requireParam(min_log_prob < 0 && min_log_prob >= -1e6, s, "min_log_prob", min_log_prob,
               "in [-1e6, 0)");
  requireParam(cluster_tolerance > 0 && cluster_tolerance <= 100, s, "cluster_tolerance",
               cluster_tolerance, "in (0, 100]");
  requireParam(cluster_min_points >= 1 && cluster_min_points <= 1000000000, s,
               "cluster_min_points", cluster_min_points, "in [1, 1e9]");
  requireParam(rtrees_max_depth >= 1 && rtrees_max_depth <= 64, s, "rtrees_max_depth",
               rtrees_max_depth, "in [1, 64]");
  requireParam(rtrees_trees >= 1 && rtrees_trees <= 10000, s, "rtrees_trees", rtrees_trees,
               "in [1, 10000]");
  requireParam(rtrees_min_samples >= 1 && rtrees_min_samples <= 1000000000, s,
               "rtrees_min_samples", rtrees_min_samples, "in [1, 1e9]");
  requireParam(knn_k >= 1 && knn_k <= 32, s, "knn_k", knn_k, "in 1..32");
  requireParam(knn_max_mean_distance > 0 && knn_max_mean_distance <= 100, s,
               "knn_max_mean_distance", knn_max_mean_distance, "in (0, 100]");
  requireParam(trace_eps > 0 && trace_eps <= 100, s, "trace_eps", trace_eps, "in (0, 100]");
  requireParam(trace_min_points >= 1 && trace_min_points <= 1000000000, s,
               "trace_min_points", trace_min_points, "in [1, 1e9]");
  requireParam(trace_max_voxels >= 1 && trace_max_voxels <= 1000000000, s,
               "trace_max_voxels", trace_max_voxels, "in [1, 1e9]");
  requireParam(trace_max_length > 0 && trace_max_length <= 10000, s, "trace_max_length",
               trace_max_length, "in (0, 1e4]");
  requireParam(seen_through_margin > 0 && seen_through_margin <= 100, s,
               "seen_through_margin", seen_through_margin, "in (0, 100]");
  requireParam(seen_through_window >= 0 && seen_through_window <= 5, s, "seen_through_window",
               seen_through_window, "in [0, 5]");
  requireParam(seen_through_window_thin >= 0 && seen_through_window_thin <= 5, s,
               "seen_through_window_thin", seen_through_window_thin, "in [0, 5]");
  requireParam(seen_through_min_scans >= 1, s, "seen_through_min_scans", seen_through_min_scans,
               ">= 1");
  requireParam(seen_through_min_ratio >= 0 && seen_through_min_ratio <= 1, s,
               "seen_through_min_ratio", seen_through_min_ratio, "in [0, 1]");
  requireParam(seen_through_vote_radius >= 0 && seen_through_vote_radius <= 5, s,
               "seen_through_vote_radius", seen_through_vote_radius, "in [0, 5]");
  requireParam(seen_through_vote_share > 0 && seen_through_vote_share <= 1, s,
               "seen_through_vote_share", seen_through_vote_share, "in (0, 1]");
  requireParam(topdown_resolution >= 0.001 && topdown_resolution <= 100, s,
               "topdown_resolution", topdown_resolution, "in [0.001, 100]");
  requireParam(num_threads >= 1 && num_threads <= 1024, s, "num_threads", num_threads,
               "in [1, 1024]");
}

json runLidarSemanticMap(const fs::path& drive_dir, const fs::path& output,
                         const LidarSemanticMapParams& p) {
  p.validate();
  io::OutputTransaction outputs(output);  // locked and writable before the work (exit 4)
  const auto t_start = Clock::now();
  json timings, summary;
  // Inputs.
  auto t = Clock::now();
  const io::KittiRawDrive drive = io::openKittiRawDrive(drive_dir, detail::frameRange(p));
  const auto fusion_settings = detail::fusionSettings(p, drive);
  lidar::ClusterClassifier classifier;
  if (!p.classifier_dir.empty()) classifier = lidar::ClusterClassifier::load(p.classifier_dir);
  lidar::FrameSemantics semantics(
      drive, detail::semanticsSettings(p, p.cache_semantics ? output / "semantics_02" : ""));
  timings["open"] = since(t);
  MAPFUSE_INFO(kStage << ": " << drive.frames.size() << " frames of " << drive.dir);

  // Poses.
  t = Clock::now();
  json pose_report;
  const std::vector<Pose3> poses = drivePoses(drive, p, pose_report);
  timings["poses"] = since(t);

  // Incremental semantic labelling, frame by frame.
  lidar::SemanticVoxelMap map(p.voxel_size, static_cast<float>(p.min_log_prob));
  const Eigen::Matrix<double, 3, 4> P = drive.calib.veloToImage2();
  double t_sem = 0, t_proj = 0, t_em = 0, t_fuse = 0, t_load = 0;
  std::size_t projected = 0, fused = 0, clusters = 0, rejected = 0, rejected_points = 0;
  Progress progress("frames", drive.frames.size());
  for (std::size_t i = 0; i < drive.frames.size(); ++i) {
    const auto& f = drive.frames[i];
    t = Clock::now();
    const io::VelodyneScan scan = io::readVelodyneBin(f.velodyne);
    t_load += since(t);
    t = Clock::now();
    const io::SemanticImage sem = semantics.get(f);
    t_sem += since(t);
    const auto st =
        lidar::fuseFrame(map, scan.points, poses[i], P, sem, classifier, fusion_settings);
    t_proj += st.t_projection;
    t_em += st.t_error_min;
    t_fuse += st.t_fusion;
    projected += st.projected;
    fused += st.fused_points;
    clusters += st.error_min.clusters;
    rejected += st.error_min.rejected_clusters;
    rejected_points += st.error_min.rejected_points;
    progress.advance();
  }
  progress.finish();
  const std::size_t voxels_fused = map.size();
  const double bytes_per_voxel_peak =
      map.empty() ? 0.0 : static_cast<double>(map.memoryBytes()) / static_cast<double>(map.size());
  map.shrinkToFit();
  const double bytes_per_voxel =
      map.empty() ? 0.0 : static_cast<double>(map.memoryBytes()) / static_cast<double>(map.size());
  timings["load_scans"] = t_load;
  timings["semantics"] = t_sem;
  timings["projection"] = t_proj;
  timings["error_minimization"] = t_em;
  timings["fusion"] = t_fuse;
  timings["per_frame_labelling_excluding_network"] =
      (t_proj + t_em + t_fuse) / static_cast<double>(drive.frames.size());

  // Batch refinement (§2.2).
  json refinement = {{"enabled", p.refine}};
  lidar::RemovedVoxelLabels removed;  // out of the map, still labelled in the scans
  auto removeVoxels = [&](const std::vector<uint8_t>& keep, bool trace) {
    for (std::size_t i = 0; i < keep.size(); ++i)
      if (!keep[i]) removed[map.voxels()[i].key] = {map.voxels()[i].label, trace};
    map.filter(keep);
  };
  t = Clock::now();
  if (p.refine) {
    const std::size_t before = map.size();
    removeVoxels(lidar::knnMeanDistanceFilter(map, detail::knnSettings(p)), false);
    refinement["knn_removed_voxels"] = before - map.size();
    timings["refinement_knn"] = since(t);
    if (p.remove_vehicle_traces && p.trace_seen_through) {
      const auto t2 = Clock::now();
      lidar::SeenThroughFilter seen(map, detail::seenThroughSettings(p));
      for (std::size_t i = 0; i < drive.frames.size(); ++i)
        seen.addScan(io::readVelodyneBin(drive.frames[i].velodyne).points, poses[i]);
      lidar::SeenThroughStats ss;
      removeVoxels(seen.keepMask(&ss), true);
      refinement["seen_through_tested_voxels"] = ss.tested_voxels;
      refinement["seen_through_removed_voxels"] = ss.removed_voxels;
      timings["refinement_seen_through"] = since(t2);
    }
    if (p.remove_vehicle_traces) {
      const auto t2 = Clock::now();
      lidar::VehicleTraceStats ts;
      removeVoxels(lidar::vehicleTraceFilter(map, detail::traceSettings(p), &ts), true);
      refinement["vehicle_voxels"] = ts.vehicle_voxels;
      refinement["vehicle_clusters"] = ts.clusters;
      refinement["trace_clusters_removed"] = ts.removed_clusters;
      refinement["trace_voxels_removed"] = ts.removed_voxels;
      timings["refinement_traces"] = since(t2);
    }
  }

  // Outputs.
  t = Clock::now();
  const LabeledCloud cloud = lidar::toLabeledCloud(map);
  io::writePly(output / "map.ply", cloud);
  io::writePcd(output / "map.pcd", cloud);
  Eigen::Vector2d topdown_origin;
  cv::Mat img = lidar::renderTopDown(map, p.topdown_resolution, &topdown_origin);
  {  // key: classes drawn, the trajectory, scale bar, north arrow (io/picture_key.hpp)
    const std::array<uint8_t, 3> path_rgb{230, 0, 0};
    std::vector<Eigen::Vector3d> path;
    for (const Pose3& T : poses) path.push_back(T.translation());
    const int path_shown = io::drawPath(img, path, topdown_origin, p.topdown_resolution, path_rgb);
    std::set<LidarClass> present;
    for (const auto& v : map.voxels()) present.insert(static_cast<LidarClass>(v.label));
    io::PictureKey key{io::lidarLegend(present), p.topdown_resolution, true, "top down"};
    if (path_shown > 0) key.legend.push_back({"trajectory", path_rgb, true});
    io::writePngFrame(output / "topdown.png", io::withPictureKey(img, key));
  }
  io::writeKittiOdometryPoses(output / "poses.txt",
                              lidar::cameraPosesForFile(poses, drive.calib.T_rect0_velo()));
  io::writeKittiOdometryPoses(output / "poses_velo.txt", poses);
  std::size_t label_files = 0, labelled_points = 0, scan_points = 0;
  if (p.write_scan_labels) {
    for (std::size_t i = 0; i < drive.frames.size(); ++i) {
      const auto& f = drive.frames[i];
      const auto scan = io::readVelodyneBin(f.velodyne);
      const auto labels = lidar::scanLabels(map, poses[i], scan.points, &removed);
      for (uint32_t l : labels) labelled_points += l != 0;
      scan_points += labels.size();
      io::writeSemanticKittiLabels(output / "labels" / (f.name + ".label"), labels);
      ++label_files;
    }
  }
  timings["outputs"] = since(t);
  timings["total"] = since(t_start);

  json hist = json::object();
  std::array<std::size_t, kNumLidarClasses> counts{};
  for (uint8_t l : cloud.labels) ++counts[l];
  for (int c = 0; c < kNumLidarClasses; ++c) hist[lidarClassName(LidarClass(c))] = counts[c];

  summary["drive"] = drive.dir.string();
  summary["frames"] = drive.frames.size();
  summary["first_frame"] = drive.frames.front().index;
  summary["last_frame"] = drive.frames.back().index;
  summary["poses"] = pose_report;
  summary["semantics"] = {{"source", semantics.source()},
                          {"from_precomputed", semantics.fromPrecomputed()},
                          {"from_cache", semantics.fromCache()},
                          {"from_network", semantics.fromNetwork()},
                          {"network_seconds", semantics.networkSeconds()}};
  json em = {{"clusters", clusters},
             {"rejected_clusters", rejected},
             {"rejected_points", rejected_points}};
  if (classifier.empty()) {
    em["skipped"] = true;
    em["reason"] = p.classifier_dir.empty() ? "no classifier_dir given"
                                            : "no rtrees_<label>.yml in classifier_dir";
    MAPFUSE_INFO(kStage << ": error minimisation skipped (" << em["reason"].get<std::string>()
                        << ")");
  } else {
    em["skipped"] = false;
    em["labels"] = classifier.labels();
  }
  summary["error_minimization"] = em;
  summary["points_projected"] = projected;
  summary["points_fused"] = fused;
  summary["voxels_after_fusion"] = voxels_fused;
  summary["voxels"] = map.size();
  summary["bytes_per_voxel"] = bytes_per_voxel;
  summary["bytes_per_voxel_before_shrink"] = bytes_per_voxel_peak;
  summary["refinement"] = refinement;
  summary["label_histogram"] = hist;
  summary["scan_label_files"] = label_files;
  summary["scan_points_labelled_fraction"] =
      scan_points ? static_cast<double>(labelled_points) / static_cast<double>(scan_points) : 0.0;
  summary["topdown"] = {{"resolution_m", p.topdown_resolution},
                        {"origin_xy", {topdown_origin.x(), topdown_origin.y()}},
                        {"width", img.cols},
                        {"height", img.rows}};
  summary["timings_s"] = timings;
  io::writeResolvedConfig(output, kStage, paramsToJson(p));
  io::writeSummary(output, kStage, summary);
  outputs.commit();  // every output replaced as a set: a failed run above left the previous ones
  return summary;
}

}  // namespace mapfuse::stages
