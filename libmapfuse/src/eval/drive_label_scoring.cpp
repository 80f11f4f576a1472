#include "mapfuse/eval/drive_label_scoring.hpp"

#include "mapfuse/core/error.hpp"
#include "mapfuse/eval/voxel_checks.hpp"
#include "mapfuse/io/ply.hpp"
#include "mapfuse/io/semantic_kitti.hpp"
#include "mapfuse/io/velodyne.hpp"
#include "mapfuse/lidar/drive_poses.hpp"

namespace mapfuse::eval {
namespace {

std::filesystem::path truthLabels(const io::KittiRawDrive& d, const io::KittiRawFrame& f) {
  return d.dir / "labels" / (f.name + ".label");
}

/// Poses of the truth scans in the map's frame (docs/evaluate.md).
std::vector<Pose3> truthPoses(const io::KittiRawDrive& drive, const std::filesystem::path& dir,
                              const TruthPoseSource& P) {
  const std::filesystem::path file = P.poses_file.empty() ? drive.poses_file : P.poses_file;
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

/// Truth voxels from every labelled scan of the drive, in the map's frame.
VoxelTruth buildTruthVoxels(const io::KittiRawDrive& drive, const std::vector<Pose3>& poses,
                            const VoxelTruthSettings& S) {
  VoxelTruth truth(S.voxel_size);
  const Eigen::Matrix<double, 3, 4> P2 = drive.calib.veloToImage2();
  for (std::size_t k = 0; k < drive.frames.size(); ++k) {
    const auto& f = drive.frames[k];
    const io::VelodyneScan scan = io::readVelodyneBin(f.velodyne);
    const auto labels = io::readSemanticKittiLabels(truthLabels(drive, f));
    if (labels.size() != scan.size())
      throw InputError(truthLabels(drive, f).string() + ": " + std::to_string(labels.size()) +
                       " labels for " + std::to_string(scan.size()) + " points");
    addLabelledScan(truth, scan.points, labels, poses[k], S.min_range, S.max_range,
                    S.camera_fov ? &P2 : nullptr, drive.calib.image_width,
                    drive.calib.image_height);
  }
  return truth;
}

}  // namespace

DriveLabelScoring scorePredictedScans(const io::KittiRawDrive& drive,
                                      const std::filesystem::path& drive_dir,
                                      const std::filesystem::path& predicted_labels) {
  DriveLabelScoring out;
  std::size_t scans = 0;
  for (const auto& f : drive.frames) {
    const auto pred = io::readSemanticKittiLabels(predicted_labels / (f.name + ".label"));
    const auto truth = io::readSemanticKittiLabels(truthLabels(drive, f));
    try {
      out.confusion += compareScanLabels(pred, truth);
    } catch (const InputError& e) {
      throw InputError(f.name + ".label: " + e.what());
    }
    ++scans;
  }
  out.doc = {{"mode", "scans"}, {"counts", {{"scans", scans}}}};
  out.problems = scanLabelProblems(scoreConfusion(out.confusion), drive_dir.string());
  return out;
}

DriveLabelScoring scoreVoxelMap(const io::KittiRawDrive& drive,
                                const std::filesystem::path& drive_dir,
                                const std::filesystem::path& map_file,
                                const VoxelTruthSettings& settings, const TruthPoseSource& poses) {
  const VoxelTruth truth = buildTruthVoxels(drive, truthPoses(drive, drive_dir, poses), settings);
  const LabeledCloud map = io::readPly(map_file);
  const MapComparison cmp = compareVoxelMap(map, truth);
  DriveLabelScoring out;
  out.confusion = cmp.confusion;
  out.problems = voxelMapProblems(cmp, map_file.string(), drive_dir.string());
  const auto share = [](uint64_t a, uint64_t b) {
    return b ? nlohmann::json(double(a) / double(b)) : nlohmann::json();
  };
  out.doc = {
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
  return out;
}

}  // namespace mapfuse::eval
