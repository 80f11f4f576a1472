#include "mapfuse/lidar/classifier_training.hpp"

#include <algorithm>

#include "mapfuse/core/classes.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/core/progress.hpp"
#include "mapfuse/io/semantic_kitti.hpp"
#include "mapfuse/io/velodyne.hpp"
#include "mapfuse/lidar/error_minimization.hpp"

namespace mapfuse::lidar {
namespace fs = std::filesystem;
namespace {

/// Adds the clusters of one drive's labelled frames to `samples`.
TrainingDriveStats collectSamples(const io::KittiRawDrive& drive, const SemanticMapSettings& s,
                                  const fs::path& cache_dir,
                                  std::array<LabelSamples, kNumLidarClasses>& samples) {
  const fs::path label_dir = drive.dir / "labels";
  if (!fs::is_directory(label_dir))
    throw IoError(label_dir.string(), "training drive has no labels/ folder");
  const FrameFusionSettings& fusion = s.fusion;
  std::array<bool, kNumLidarClasses> mask{};
  for (int l = 1; l < kNumLidarClasses; ++l) mask[l] = true;  // no forest for "unlabeled"
  FrameSemantics semantics(drive, s.semantics, cache_dir);
  const ImageProjection camera = ImageProjection::of(drive.calib);
  TrainingDriveStats st;
  st.drive = drive.dir.string();
  Progress progress("training frames", drive.frames.size());
  for (const auto& f : drive.frames) {
    progress.advance();
    const fs::path lp = label_dir / (f.name + ".label");
    if (!fs::exists(lp)) {
      ++st.frames_without_labels;
      continue;
    }
    const auto scan = io::readVelodyneBin(f.velodyne);
    const auto gt = io::readSemanticKittiLabels(lp);
    if (gt.size() != scan.size())
      throw ParseError(lp.string(), "size",
                       std::to_string(gt.size()) + " labels for " + std::to_string(scan.size()) +
                           " scan points");
    const auto proj = labelScan(scan.points, camera, semantics.get(f), fusion.projection);
    std::vector<uint8_t> truth(proj.points.size());
    for (std::size_t k = 0; k < truth.size(); ++k) {
      truth[k] = static_cast<uint8_t>(
          lidarClassFromSemanticKitti(io::semanticIdOf(gt[proj.scan_index[k]])));
      ++samples[truth[k]].truth_points;
    }
    const auto cl = labelClusters(proj.points, proj.labels, fusion.clustering, mask);
    for (const auto& c : cl) {  // correct when the majority of the true labels agrees
      std::array<int, kNumLidarClasses> votes{};
      for (int m : c.members) ++votes[truth[m]];
      const int majority =
          static_cast<int>(std::max_element(votes.begin(), votes.end()) - votes.begin());
      LabelSamples& ls = samples[c.label];
      ls.features.push_back(c.features);
      ls.correct.push_back(majority == c.label ? 1 : 0);
      ls.points.push_back(static_cast<int>(c.members.size()));
      ls.correct_points.push_back(votes[c.label]);
    }
    st.clusters += cl.size();
    ++st.frames_used;
  }
  progress.finish();
  st.semantics = semantics.source();
  return st;
}
}  // namespace

ClassifierTrainingResult trainClusterClassifier(const std::vector<fs::path>& drives,
                                                const std::vector<fs::path>& validation,
                                                const io::FrameRange& frames,
                                                const SemanticMapSettings& map,
                                                const RTreesSettings& rtrees,
                                                const fs::path& cache_root) {
  if (drives.empty()) throw InputError("train: no labelled drive given");
  ClassifierTrainingResult r;
  std::array<LabelSamples, kNumLidarClasses> samples;
  for (const fs::path& dir : drives) {
    const io::KittiRawDrive drive = io::openKittiRawDrive(dir, frames);
    const fs::path cache = cache_root.empty() ? fs::path() : cache_root / drive.dir.filename();
    r.drives.push_back(collectSamples(drive, map, cache, samples));
    r.frames_used += r.drives.back().frames_used;
  }
  if (r.frames_used == 0) throw InputError("train: no frame with a labels/<frame>.label file");
  r.classifier = ClusterClassifier::train(samples, rtrees, &r.report);
  if (validation.empty()) {
    MAPFUSE_WARN(
        "train: no validation drive: every forest filters at its majority vote (0.5), "
        "even one that costs its label IoU");
    return r;
  }
  std::vector<std::array<LabelSamples, kNumLidarClasses>> held(validation.size());
  for (std::size_t d = 0; d < validation.size(); ++d) {
    const io::KittiRawDrive drive = io::openKittiRawDrive(validation[d], frames);
    const fs::path cache = cache_root.empty() ? fs::path() : cache_root / drive.dir.filename();
    r.validation_drives.push_back(collectSamples(drive, map, cache, held[d]));
  }
  r.validated = true;
  for (int l = 1; l < kNumLidarClasses; ++l) {
    const auto label = static_cast<LidarClass>(l);
    if (!r.classifier.has(label)) continue;
    std::vector<ValidationSet> sets(held.size());
    for (std::size_t d = 0; d < held.size(); ++d) {
      sets[d].samples = std::move(held[d][l]);
      for (const ClusterFeatures& f : sets[d].samples.features)
        sets[d].correct_votes.push_back(r.classifier.correctVotes(label, f));
    }
    ThresholdChoice& c = r.thresholds[l] =
        chooseThreshold(sets, rtrees.min_validation_gain, rtrees.gain_tolerance);
    if (c.used) {
      r.classifier.setThreshold(label, c.min_correct_votes);
    } else {
      r.classifier.remove(label);
      MAPFUSE_INFO("train: no forest for " << lidarClassName(label) << ": " << c.reason);
    }
  }
  return r;
}

}  // namespace mapfuse::lidar
