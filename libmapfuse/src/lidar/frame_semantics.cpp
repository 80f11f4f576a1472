#include "mapfuse/lidar/frame_semantics.hpp"

#include <chrono>
#include <opencv2/imgcodecs.hpp>

#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/core/paths.hpp"

namespace mapfuse::lidar {
namespace fs = std::filesystem;

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
