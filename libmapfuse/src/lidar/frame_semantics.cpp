#include "mapfuse/lidar/frame_semantics.hpp"

#include <chrono>
#include <opencv2/imgcodecs.hpp>

#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/core/paths.hpp"

namespace mapfuse::lidar {
namespace fs = std::filesystem;

namespace {
/// Refuses, before any work, a drive whose class evidence cannot exist: ENet with no camera
/// image in the selected frames, or a sequence without image_2 (its image size is unknown, so
/// neither ENet nor precomputed semantics can be projected into).
void requireImages(const io::KittiRawDrive& drive, const std::string& source) {
  bool any = false;
  for (const auto& f : drive.frames) any = any || !f.image.empty();
  if (any && drive.calib.image_width > 0 && drive.calib.image_height > 0) return;
  if (source == "precomputed" && drive.calib.image_width > 0) return;
  const bool sequence = drive.layout == "sequence";
  throw IoError((drive.dir / (sequence ? "image_2" : "image_02/data")).string(),
                "no camera image in the selected frames: lidar-semantic-map labels each LiDAR "
                "point from the camera picture it projects into (docs/kitti.md \"Without "
                "images\"); evaluate voxels reads the drive without them");
}
}  // namespace

FrameSemantics::FrameSemantics(const io::KittiRawDrive& drive, const FrameSemanticsSettings& s,
                               const fs::path& cache_dir)
    : s_(s), cache_dir_(s.cache ? cache_dir : fs::path()) {
  pre_dir_ = s.semantics_dir.empty() ? io::semanticsDir(drive.dir) : fs::path(s.semantics_dir);
  if (s.segmenter == "auto") {
    bool any = false;
    for (const char* ext : {".prob", ".png"})
      any = any || fs::exists(pre_dir_ / (drive.frames.front().name + ext));
    source_ = any ? "precomputed" : "enet";
  } else if (s.segmenter == "enet" || s.segmenter == "precomputed") {
    source_ = s.segmenter;
  } else {
    throw ConfigError("segmenter = \"" + s.segmenter +
                      "\". Violated constraint: one of auto, enet, precomputed");
  }
  requireImages(drive, source_);
  if (source_ == "precomputed" && !fs::is_directory(pre_dir_))
    throw IoError(pre_dir_.string(), "precomputed semantics folder not found");
  const fs::path model =
      s.model.empty() ? sharedRoot() / "models/enet-cityscapes/enet-model.net" : fs::path(s.model);
  if (source_ == "enet") enet_ = std::make_unique<EnetSegmenter>(model, s.enet);
  MAPFUSE_INFO("semantics: " << source_
                             << (source_ == "precomputed" ? " from " + pre_dir_.string() : ""));
}

FrameSemantics::~FrameSemantics() = default;

io::SemanticImage FrameSemantics::get(const io::KittiRawFrame& frame) {
  if (source_ == "precomputed") {
    const fs::path dir = pre_dir_;
    for (const char* ext : {".prob", ".png"}) {
      const fs::path p = dir / (frame.name + ext);
      if (fs::exists(p)) {
        ++n_pre_;
        return io::readSemanticImage(p);
      }
    }
    throw IoError((dir / (frame.name + ".png")).string(),
                  "no precomputed semantics (.prob or .png) for frame " + frame.name);
  }
  if (!cache_dir_.empty()) {
    const fs::path cached = cache_dir_ / (frame.name + ".prob");
    if (fs::exists(cached)) {
      ++n_cache_;
      return io::readSemanticImage(cached);
    }
  }
  if (frame.image.empty())
    throw IoError(frame.velodyne.string(), "frame " + frame.name + " has no image_02 for ENet");
  const cv::Mat bgr = cv::imread(frame.image.string(), cv::IMREAD_COLOR);
  if (bgr.empty()) throw IoError(frame.image.string(), "cannot decode image");
  const auto t0 = std::chrono::steady_clock::now();
  io::SemanticImage sem = enet_->segment(bgr);
  t_net_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ++n_net_;
  if (!cache_dir_.empty()) io::writeSemanticImage(cache_dir_ / (frame.name + ".prob"), sem);
  return sem;
}

}  // namespace mapfuse::lidar
