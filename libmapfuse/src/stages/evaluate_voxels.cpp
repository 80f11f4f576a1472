#include "mapfuse/stages/evaluate_voxels.hpp"

#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/eval/input_problems.hpp"
#include "mapfuse/eval/voxel_checks.hpp"
#include "mapfuse/eval/voxel_metrics.hpp"
#include "mapfuse/eval/voxel_truth.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/kitti_raw.hpp"
#include "mapfuse/io/output_transaction.hpp"
#include "mapfuse/io/ply.hpp"
#include "mapfuse/io/semantic_kitti.hpp"
#include "mapfuse/io/stage_report.hpp"
#include "mapfuse/io/velodyne.hpp"
#include "mapfuse/lidar/drive_poses.hpp"

namespace mapfuse::stages {
namespace {
constexpr const char* kStage = "evaluate-voxels";

std::filesystem::path truthLabels(const io::KittiRawDrive& d, const io::KittiRawFrame& f) {
  return d.dir / "labels" / (f.name + ".label");
}
/// Poses of the truth scans in the map's frame (docs/evaluate.md).
std::vector<Pose3> truthPoses(const io::KittiRawDrive& drive, const std::filesystem::path& dir,
                              const EvaluateVoxelsParams& P) {
  const std::filesystem::path file =
      P.poses_file.empty() ? drive.poses_file : std::filesystem::path(P.poses_file);
  std::string src = P.pose_source;
  if (src == "auto") src = drive.has_oxts ? "oxts" : "poses_file";
  if (src == "poses_file") {
    if (file.empty())
      throw InputError(dir.string() +
                       ": truth voxels need poses: no OXTS, give --poses-file (e.g. the map's "
                       "poses.txt)");
    return lidar::veloPosesFromFile(drive, file);
  }
  if (!drive.has_oxts) throw InputError(dir.string() + ": truth voxels need OXTS poses");
  std::vector<Pose3> poses = lidar::oxtsVeloPoses(drive, src == "oxts-enu");
  if (P.recenter) lidar::recenter(poses);
  return poses;
}
}  // namespace

nlohmann::json runEvaluateVoxels(const EvaluateVoxelsInputs& in, const std::filesystem::path& out,
                                 const EvaluateVoxelsParams& P) {
  validateParams(P);
  io::OutputTransaction outputs(out);  // locked and writable before the work (exit 4)
  if (in.map.empty() == in.predicted_labels.empty())
    throw InputError(
        "evaluate voxels: give exactly one of a voxel map or a predicted labels folder");
  const io::KittiRawDrive drive = io::openKittiRawDrive(in.drive, io::FrameRange{});
  nlohmann::json doc;
  eval::ConfusionMatrix confusion;
  std::vector<std::string> problems, noted;  // inputs that cannot be scored
  if (!in.predicted_labels.empty()) {
    // (b) per-scan predictions vs truth, point by point.
    std::size_t scans = 0;
    for (const auto& f : drive.frames) {
      const auto pred = io::readSemanticKittiLabels(in.predicted_labels / (f.name + ".label"));
      const auto truth = io::readSemanticKittiLabels(truthLabels(drive, f));
      try {
        confusion += eval::compareScanLabels(pred, truth);
      } catch (const InputError& e) {
        throw InputError(f.name + ".label: " + e.what());
      }
      ++scans;
    }
    doc = {{"mode", "scans"}, {"counts", {{"scans", scans}}}};
    problems = eval::scanLabelProblems(eval::scoreConfusion(confusion), in.drive.string());
  } else {
    // (a) voxel map vs truth voxels from the labelled scans in the same frame.
    std::vector<Pose3> poses = truthPoses(drive, in.drive, P);
    eval::VoxelTruth truth(P.truth.voxel_size);
    const Eigen::Matrix<double, 3, 4> P2 = drive.calib.veloToImage2();
    for (std::size_t k = 0; k < drive.frames.size(); ++k) {
      const auto& f = drive.frames[k];
      const io::VelodyneScan scan = io::readVelodyneBin(f.velodyne);
      const auto labels = io::readSemanticKittiLabels(truthLabels(drive, f));
      if (labels.size() != scan.size())
        throw InputError(truthLabels(drive, f).string() + ": " + std::to_string(labels.size()) +
                         " labels for " + std::to_string(scan.size()) + " points");
      eval::addLabelledScan(truth, scan.points, labels, poses[k], P.truth.min_range,
                            P.truth.max_range, P.truth.camera_fov ? &P2 : nullptr,
                            drive.calib.image_width, drive.calib.image_height);
    }
    const LabeledCloud map = io::readPly(in.map);
    const eval::MapComparison cmp = eval::compareVoxelMap(map, truth);
    confusion = cmp.confusion;
    problems = eval::voxelMapProblems(cmp, in.map.string(), in.drive.string());
    const auto share = [](uint64_t a, uint64_t b) {
      return b ? nlohmann::json(double(a) / double(b)) : nlohmann::json();
    };
    doc = {
        {"mode", "voxels"},
        {"counts",
         {{"scans", drive.frames.size()},
          {"map_voxels", cmp.map_voxels},
          {"unmatched_map_voxels", cmp.unmatched},
          {"truth_voxels", cmp.truth_voxels}}},
        {"trace_removal",
         {{"moving_truth_voxels", cmp.moving_truth},
          {"moving_voxels_in_map", cmp.moving_in_map},
          {"moving_removed_share", share(cmp.moving_truth - cmp.moving_in_map, cmp.moving_truth)},
          {"parked_truth_voxels", cmp.parked_truth},
          {"parked_voxels_in_map", cmp.parked_in_map},
          {"parked_kept_share", share(cmp.parked_in_map, cmp.parked_truth)}}}};
  }
  eval::warnOrRefuse(problems, P.strict, "evaluate voxels", noted);
  const eval::LabelScores scores = eval::scoreConfusion(confusion);
  doc["scores"] = eval::scoresToJson(scores);
  doc["problems"] = noted;
  const std::string md = eval::scoresToMarkdown(scores, P.title);
  io::writeDocument(out / "voxels.json", doc);
  io::writeBytesAtomic(out / "voxels.md", md);
  io::writeResolvedConfig(out, kStage, paramsToJson(P));
  io::writeSummary(out, kStage,
                   {{"mode", doc["mode"]},
                    {"mean_iou", doc["scores"]["mean_iou"]},
                    {"mean_accuracy", doc["scores"]["mean_accuracy"]},
                    {"evaluated", scores.evaluated},
                    {"undefined_reason", eval::undefinedScoreReason(scores)},
                    {"problems", noted}});
  outputs.commit();
  doc["markdown"] = md;
  return doc;
}

}  // namespace mapfuse::stages
