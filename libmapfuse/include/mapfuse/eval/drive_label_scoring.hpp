#pragma once
/// @file The two comparisons of `evaluate voxels` (docs/evaluate.md) against a KITTI raw drive's
/// labelled scans: (a) a semantic voxel map against truth voxels built from the scans with the
/// drive's poses, (b) per-scan `.label` predictions against the truth `.label` files, point by
/// point. Both give the confusion matrix of Jeong et al. 2018's eq. 10-11 scores.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mapfuse/eval/voxel_metrics.hpp"
#include "mapfuse/eval/voxel_truth.hpp"
#include "mapfuse/io/kitti_raw.hpp"

namespace mapfuse::eval {

/// What one comparison found: the voxels.json document without its scores, the confusion
/// matrix, and the inputs that cannot be scored (eval::voxelMapProblems / scanLabelProblems).
struct DriveLabelScoring {
  nlohmann::json doc;  ///< {"mode", "counts", "trace_removal"?}
  ConfusionMatrix confusion;
  std::vector<std::string> problems;
};

/// Where the poses of the truth scans come from (the stage's pose parameters).
struct TruthPoseSource {
  std::string pose_source = "auto";  ///< auto | oxts | oxts-enu | poses_file
  std::filesystem::path poses_file;  ///< empty: the drive's own poses file
  bool recenter = true;              ///< first OXTS pose at the origin
};

/// @brief (b) Every `<predicted_labels>/<frame>.label` against the drive's truth labels.
/// @throws InputError naming the frame when sizes disagree; IoError / ParseError.
DriveLabelScoring scorePredictedScans(const io::KittiRawDrive& drive,
                                      const std::filesystem::path& drive_dir,
                                      const std::filesystem::path& predicted_labels);

/// @brief (a) The voxel map `map_file` (PLY) against truth voxels built from the drive's labelled
/// scans at the poses `poses` says.
/// @throws InputError when the poses are missing or a scan's labels do not match its points.
DriveLabelScoring scoreVoxelMap(const io::KittiRawDrive& drive,
                                const std::filesystem::path& drive_dir,
                                const std::filesystem::path& map_file,
                                const VoxelTruthSettings& settings, const TruthPoseSource& poses);

}  // namespace mapfuse::eval
