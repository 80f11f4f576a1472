#include <chrono>

#include "mapfuse/core/classes.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/core/progress.hpp"
#include "mapfuse/io/output_transaction.hpp"
#include "mapfuse/io/semantic_kitti.hpp"
#include "mapfuse/io/stage_report.hpp"
#include "mapfuse/io/velodyne.hpp"
#include "mapfuse/lidar/error_minimization.hpp"
#include "mapfuse/stages/lidar_semantic_map.hpp"
#include "mapfuse/stages/lidar_semantic_map_detail.hpp"

namespace mapfuse::stages {
namespace fs = std::filesystem;
using json = nlohmann::json;

json runLidarSemanticMapTrain(const std::vector<fs::path>& drives, const fs::path& output,
                              const LidarSemanticMapParams& p) {
  p.validate();
  io::OutputTransaction outputs(output);  // locked and writable before the work (exit 4)
  if (drives.empty()) throw InputError("train: no labelled drive given");
  const auto t_start = std::chrono::steady_clock::now();
  std::array<lidar::LabelSamples, kNumLidarClasses> samples;
  std::array<bool, kNumLidarClasses> mask{};
  for (int l = 1; l < kNumLidarClasses; ++l) mask[l] = true;  // no forest for "unlabeled"
  json per_drive = json::array();
  std::size_t frames_used = 0;
  for (const fs::path& dir : drives) {
    const io::KittiRawDrive drive = io::openKittiRawDrive(dir, detail::frameRange(p));
    const fs::path label_dir = drive.dir / "labels";
    if (!fs::is_directory(label_dir))
      throw IoError(label_dir.string(), "training drive has no labels/ folder");
    const auto fs_settings = detail::fusionSettings(p, drive);
    lidar::FrameSemantics semantics(
        drive, detail::semanticsSettings(
                   p, p.cache_semantics ? output / "semantics_cache" / drive.dir.filename() : ""));
    const Eigen::Matrix<double, 3, 4> P = drive.calib.veloToImage2();
    std::size_t used = 0, skipped = 0, clusters = 0;
    Progress progress("training frames", drive.frames.size());
    for (const auto& f : drive.frames) {
      progress.advance();
      const fs::path lp = label_dir / (f.name + ".label");
      if (!fs::exists(lp)) {
        ++skipped;
        continue;
      }
      const auto scan = io::readVelodyneBin(f.velodyne);
      const auto gt = io::readSemanticKittiLabels(lp);
      if (gt.size() != scan.size())
        throw ParseError(lp.string(), "size",
                         std::to_string(gt.size()) + " labels for " + std::to_string(scan.size()) +
                             " scan points");
      const auto proj = lidar::labelScan(scan.points, P, semantics.get(f), fs_settings.projection);
      const auto cl = lidar::labelClusters(proj.points, proj.labels, fs_settings.clustering, mask);
      for (const auto& c : cl) {
        std::array<int, kNumLidarClasses> votes{};
        for (int m : c.members)
          ++votes[static_cast<int>(
              lidarClassFromSemanticKitti(io::semanticIdOf(gt[proj.scan_index[m]])))];
        const int majority =
            static_cast<int>(std::max_element(votes.begin(), votes.end()) - votes.begin());
        samples[c.label].features.push_back(c.features);
        samples[c.label].correct.push_back(majority == c.label ? 1 : 0);
      }
      clusters += cl.size();
      ++used;
    }
    progress.finish();
    frames_used += used;
    per_drive.push_back({{"drive", drive.dir.string()},
                         {"frames_used", used},
                         {"frames_without_labels", skipped},
                         {"clusters", clusters},
                         {"semantics", semantics.source()}});
  }
  if (frames_used == 0) throw InputError("train: no frame with a labels/<frame>.label file");
  lidar::TrainingReport rep;
  const auto classifier = lidar::ClusterClassifier::train(samples, detail::rtreesSettings(p), &rep);
  classifier.save(output);
  json labels = json::object();
  for (int l = 1; l < kNumLidarClasses; ++l) {
    json j = {{"correct_clusters", rep.positives[l]},
              {"wrong_clusters", rep.negatives[l]},
              {"trained", rep.trained[l]}};
    if (rep.trained[l])
      j["training_accuracy"] = rep.training_accuracy[l];
    else
      j["reason"] = "fewer than rtrees_min_samples correct or wrong clusters";
    labels[lidarClassName(LidarClass(l))] = j;
  }
  json summary = {
      {"drives", per_drive},
      {"frames_used", frames_used},
      {"labels", labels},
      {"forests", classifier.labels()},
      {"timings_s",
       {{"total",
         std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count()}}}};
  io::writeResolvedConfig(output, "lidar-semantic-map-train", paramsToJson(p));
  io::writeSummary(output, "lidar-semantic-map-train", summary);
  MAPFUSE_INFO("train: forests for " << classifier.labels().size() << " labels written to "
                                     << output);
  outputs.commit();
  return summary;
}

}  // namespace mapfuse::stages
