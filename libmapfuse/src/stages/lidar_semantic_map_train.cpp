#include "mapfuse/cli/params.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/core/stopwatch.hpp"
#include "mapfuse/io/output_transaction.hpp"
#include "mapfuse/io/stage_report.hpp"
#include "mapfuse/stages/lidar_semantic_map.hpp"

namespace mapfuse::stages {
namespace fs = std::filesystem;

lidar::ClassifierTrainingResult runLidarSemanticMapTrain(const std::vector<fs::path>& drives,
                                                         const std::vector<fs::path>& validation,
                                                         const fs::path& output,
                                                         const LidarSemanticMapParams& p) {
  validateParams(p);
  io::OutputTransaction outputs(output);  // locked and writable before the work (exit 4)
  const Stopwatch total;
  lidar::ClassifierTrainingResult r = lidar::trainClusterClassifier(
      drives, validation, p.frames, p.map, p.rtrees, output / "semantics_cache");
  r.classifier.save(output);
  nlohmann::json summary = toJson(r);
  summary["timings_s"] = {{"total", total.seconds()}};
  io::writeResolvedConfig(output, "lidar-semantic-map-train", paramsToJson(p));
  io::writeSummary(output, "lidar-semantic-map-train", summary);
  MAPFUSE_INFO("train: forests for " << r.classifier.labels().size() << " labels written to "
                                     << output);
  outputs.commit();
  return r;
}

}  // namespace mapfuse::stages
