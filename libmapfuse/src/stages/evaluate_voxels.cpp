#include "mapfuse/stages/evaluate_voxels.hpp"

#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/eval/drive_label_scoring.hpp"
#include "mapfuse/eval/input_problems.hpp"
#include "mapfuse/eval/voxel_checks.hpp"
#include "mapfuse/eval/voxel_metrics.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/document.hpp"
#include "mapfuse/io/output_transaction.hpp"
#include "mapfuse/io/stage_report.hpp"

namespace mapfuse::stages {
namespace {
constexpr const char* kEvaluateVoxels = "evaluate-voxels";

}  // namespace

nlohmann::json runEvaluateVoxels(const EvaluateVoxelsInputs& in, const std::filesystem::path& out,
                                 const EvaluateVoxelsParams& P) {
  validateParams(P);
  io::OutputTransaction outputs(out);  // locked and writable before the work (exit 4)
  if (in.map.empty() == in.predicted_labels.empty())
    throw InputError(
        "evaluate voxels: give exactly one of a voxel map or a predicted labels folder");
  const io::KittiRawDrive drive = io::openKittiRawDrive(in.drive, io::FrameRange{});
  const eval::DriveLabelScoring scored =
      in.predicted_labels.empty() ? eval::scoreVoxelMap(drive, in.drive, in.map, P.truth,
                                                        {P.pose_source, P.poses_file, P.recenter})
                                  : eval::scorePredictedScans(drive, in.drive, in.predicted_labels);
  nlohmann::json doc = scored.doc;
  std::vector<std::string> noted;  // inputs that cannot be scored
  eval::warnOrRefuse(scored.problems, P.strict, "evaluate voxels", noted);
  const eval::LabelScores scores = eval::scoreConfusion(scored.confusion);
  doc["scores"] = eval::scoresToJson(scores);
  doc["problems"] = noted;
  const std::string md = eval::scoresToMarkdown(scores, P.title);
  io::writeDocument(out / "voxels.json", doc);
  io::writeBytesAtomic(out / "voxels.md", md);
  io::writeResolvedConfig(out, kEvaluateVoxels, paramsToJson(P));
  io::writeSummary(out, kEvaluateVoxels,
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
