#pragma once
/// @file Stage `evaluate voxels`: per-class accuracy (eq. 10) and IoU (eq. 11) of Jeong et al.
/// 2018 in the paper's Table 1 layout, for (a) a semantic voxel map (PLY from
/// lidar-semantic-map) against truth voxels built from the drive's labelled scans
/// (`<drive>/labels/<frame>.label`) with the drive's poses (OXTS or a poses file), or (b) per-scan
/// `.label` predictions against the truth `.label` files. Writes voxels.json, voxels.md and
/// evaluate-voxels.{config,summary}.json in the output folder.
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "mapfuse/cli/params.hpp"
#include "mapfuse/eval/voxel_truth.hpp"

namespace mapfuse::stages {

struct EvaluateVoxelsParams {
  static constexpr const char* kName = "EvaluateVoxelsParams";
  eval::VoxelTruthSettings truth;    ///< which labelled points become truth voxels
  std::string pose_source = "auto";  ///< auto | oxts (devkit Mercator) | oxts-enu | poses_file
  std::string poses_file;            ///< T_world_cam0 poses (KITTI), e.g. the map's poses.txt
  bool recenter = true;              ///< first pose at the origin (as the map is written)
  std::string title = "mapfuse";     ///< first column of the Markdown table
  bool strict = false;  ///< refuse (exit 3) inputs that cannot be scored, instead of a warning

  template <class V>
  void visit(V& v) {
    truth.visit(v);
    v("pose_source", pose_source, "",
      "poses of the truth scans: auto (OXTS when every frame has it, else the poses file or the "
      "sequence's poses.txt), oxts (devkit), oxts-enu or poses_file",
      param::oneOf({"auto", "oxts", "oxts-enu", "poses_file"}));
    v("poses_file", poses_file, "",
      "KITTI poses file (T_world_cam0), e.g. the evaluated map's poses.txt");
    v("recenter", recenter, "", "move the first pose to the origin, as the map is written");
    v("title", title, "", "method name in the first column of the Markdown table");
    v("strict", strict, "",
      "refuse (exit 3) an empty truth, an empty map or a map that meets no truth voxel "
      "(default: a warning and a 'problems' list in the summary)");
  }
};

/// Inputs of the evaluation: exactly one of `map` and `predicted_labels`.
struct EvaluateVoxelsInputs {
  std::filesystem::path drive;             ///< KITTI raw drive with labels/ (truth)
  std::filesystem::path map;               ///< semantic voxel map (.ply), or empty
  std::filesystem::path predicted_labels;  ///< folder of <frame>.label predictions, or empty
};

/// @brief Runs the evaluation and writes the reports into `out`. Returns the voxels.json
/// document ({"mode", "scores", "counts", "trace_removal"?}).
/// @throws InputError when both or neither prediction inputs are given or sizes disagree;
/// IoError / ParseError for unreadable or malformed files.
nlohmann::json runEvaluateVoxels(const EvaluateVoxelsInputs& in, const std::filesystem::path& out,
                                 const EvaluateVoxelsParams& params);

}  // namespace mapfuse::stages
