#include "mapfuse/vehicle/mask_observations.hpp"

#include <atomic>
#include <exception>
#include <string>

#include "centerline.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/core/progress.hpp"

namespace mapfuse::vehicle {

std::vector<FrameObservations> observationsFromMaskFiles(const io::DriveFrames& df,
                                                         const std::filesystem::path& drive_dir,
                                                         int width, int height, int min_area) {
  std::vector<FrameObservations> frames(df.frames.size());
  std::vector<std::exception_ptr> errors(df.frames.size());
  Progress progress("masks", df.frames.size());
  std::atomic<bool> failed{false};
#pragma omp parallel for schedule(dynamic)
  for (int i = 0; i < int(df.frames.size()); ++i) {
    if (failed) continue;
    try {
      if (df.frames[i].mask.empty())
        throw ParseError((drive_dir / "frames.csv").string(), "frame " + std::to_string(i),
                         "no mask file named");
      const cv::Mat mask = io::readMask(df.frames[i].mask, width, height);
      frames[i].index = df.frames[i].index;
      frames[i].stamp = df.frames[i].stamp;
      frames[i].ground = observationsFromMask(mask, min_area);
      // Aerial boxes come only from observations.jsonl.
      if (!df.observations.empty()) frames[i].aerial = df.observations[i].aerial;
    } catch (...) {
      errors[i] = std::current_exception();
      failed = true;
    }
    progress.advance();
  }
  for (const auto& e : errors)  // the first failure, with its original type
    if (e) std::rethrow_exception(e);
  return frames;
}

}  // namespace mapfuse::vehicle
