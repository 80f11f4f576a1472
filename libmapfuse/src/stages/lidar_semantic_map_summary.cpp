// The summaries of lidar-semantic-map and its train subcommand, from the area results.
#include "mapfuse/core/classes.hpp"
#include "mapfuse/stages/lidar_semantic_map.hpp"

namespace mapfuse::stages {
using json = nlohmann::json;

namespace {
json timingsJson(const lidar::SemanticMapResult& r, std::size_t frames) {
  const auto& t = r.timings;
  json j = {{"open", t.open},
            {"poses", t.poses},
            {"load_scans", t.load_scans},
            {"semantics", t.semantics},
            {"projection", t.projection},
            {"error_minimization", t.error_minimization},
            {"fusion", t.fusion},
            {"wait_inputs", t.wait_inputs},
            {"frames", t.frames},
            {"frames_per_second", t.frames > 0 ? static_cast<double>(frames) / t.frames : 0.0},
            {"per_frame_labelling_excluding_network",
             (t.projection + t.error_minimization + t.fusion) / static_cast<double>(frames)}};
  if (r.refinement.ran) j["refinement_knn"] = r.refinement.seconds_knn;
  if (r.refinement.ran_seen_through)
    j["refinement_seen_through"] = r.refinement.seconds_seen_through;
  if (r.refinement.ran_traces) j["refinement_traces"] = r.refinement.seconds_traces;
  return j;
}
}  // namespace

json toJson(const lidar::SemanticMapResult& r, const lidar::DriveOdometrySettings& odometry) {
  json s;
  s["poses"] = lidar::posesReport(r.poses, odometry);
  s["semantics"] = {{"source", r.semantics.source},
                    {"from_precomputed", r.semantics.from_precomputed},
                    {"from_cache", r.semantics.from_cache},
                    {"from_network", r.semantics.from_network},
                    {"network_seconds", r.semantics.network_seconds}};
  json em = {{"clusters", r.error_min.clusters},
             {"rejected_clusters", r.error_min.rejected_clusters},
             {"rejected_points", r.error_min.rejected_points},
             {"skipped", !r.error_min_skipped.empty()}};
  if (r.error_min_skipped.empty()) {
    em["labels"] = r.forest_labels;
    em["min_correct_votes"] = r.forest_thresholds;
    em["classifier_dir"] = r.classifier_dir;
    em["provenance"] = r.forest_provenance.is_null()
                           ? json("none: the folder has no provenance.json")
                           : r.forest_provenance;
  } else {
    em["reason"] = r.error_min_skipped;
  }
  s["error_minimization"] = em;
  s["points_projected"] = r.points_projected;
  s["points_fused"] = r.points_fused;
  s["voxels_after_fusion"] = r.voxels_after_fusion;
  s["voxels"] = r.map.size();
  s["bytes_per_voxel"] = r.bytes_per_voxel;
  s["bytes_per_voxel_before_shrink"] = r.bytes_per_voxel_before_shrink;
  s["refinement"] = lidar::refinementReport(r.refinement);
  s["timings_s"] = timingsJson(r, r.poses.T_map_velo.size());
  return s;
}

namespace {
json drivesJson(const std::vector<lidar::TrainingDriveStats>& drives) {
  json per_drive = json::array();
  for (const auto& d : drives)
    per_drive.push_back({{"drive", d.drive},
                         {"frames_used", d.frames_used},
                         {"frames_without_labels", d.frames_without_labels},
                         {"clusters", d.clusters},
                         {"semantics", d.semantics}});
  return per_drive;
}
json thresholdJson(const lidar::ThresholdChoice& c) {
  json j = {{"clusters", c.clusters},
            {"forest_used", c.used},
            {"iou_unfiltered", c.iou_unfiltered},
            {"iou_filtered", c.iou_filtered},
            {"iou_majority_vote", c.iou_majority},
            {"worst_drive_gain", c.worst_gain},
            {"worst_drive_gain_at_0.05_to_0.95", c.worst_gain_by_threshold}};
  if (c.used) {
    j["min_correct_votes"] = c.min_correct_votes;
    j["rejected_clusters"] = c.rejected_clusters;
    j["rejected_correct_points"] = c.rejected_correct_points;
    j["rejected_wrong_points"] = c.rejected_wrong_points;
  } else {
    j["reason"] = c.reason;
  }
  return j;
}
}  // namespace

json toJson(const lidar::ClassifierTrainingResult& r) {
  json labels = json::object();
  for (int l = 1; l < kNumLidarClasses; ++l) {
    json j = {{"correct_clusters", r.report.positives[l]},
              {"wrong_clusters", r.report.negatives[l]},
              {"trained", r.report.trained[l]}};
    if (r.report.trained[l])
      j["training_accuracy"] = r.report.training_accuracy[l];
    else
      j["reason"] = "fewer than rtrees_min_samples correct or wrong clusters";
    if (r.validated && r.report.trained[l]) j["validation"] = thresholdJson(r.thresholds[l]);
    labels[lidarClassName(LidarClass(l))] = j;
  }
  return {{"drives", drivesJson(r.drives)},
          {"validation_drives", drivesJson(r.validation_drives)},
          {"frames_used", r.frames_used},
          {"labels", labels},
          {"forests", r.classifier.labels()}};
}

}  // namespace mapfuse::stages
