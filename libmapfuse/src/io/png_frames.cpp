#include "mapfuse/io/png_frames.hpp"

#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/atomic_file.hpp"

namespace mapfuse::io {

void writePngFrame(const std::filesystem::path& path, const cv::Mat& image) {
  std::vector<uchar> png;
  if (image.empty() || !cv::imencode(".png", image, png))
    throw IoError(path.string(), "PNG encoding failed");
  writeBytesAtomic(path, std::string(png.begin(), png.end()));
}

}  // namespace mapfuse::io
