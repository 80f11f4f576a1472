#include "segmentation_cache.hpp"

#include <opencv2/imgcodecs.hpp>

#include "mapfuse/core/error.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/png_decode.hpp"

namespace mapfuse::vehicle {
namespace fs = std::filesystem;

fs::path segmentationCachePath(const fs::path& folder, const fs::path& image) {
  return folder / (image.stem().string() + ".seg.png");
}

std::optional<Segmentation> readCachedSegmentation(const fs::path& file, const cv::Size& size) {
  if (!fs::exists(file)) return std::nullopt;
  const cv::Mat img = io::decodePng(io::readBytes(file), file.string(), cv::IMREAD_UNCHANGED);
  if (img.type() != CV_8UC3)
    throw ParseError(file.string(), "", "a segmentation cache file must be 8-bit, 3 channels");
  if (img.size() != size)
    throw ParseError(file.string(), "",
                     "size " + std::to_string(img.cols) + "x" + std::to_string(img.rows) +
                         " differs from its image " + std::to_string(size.width) + "x" +
                         std::to_string(size.height) + " (stale cache? delete the folder)");
  Segmentation seg;
  cv::Mat ch[3];
  cv::split(img, ch);
  seg.classes = ch[0];
  seg.confidence = ch[1];
  double mx = 0;
  cv::minMaxLoc(seg.classes, nullptr, &mx);
  if (mx >= 20)
    throw ParseError(
        file.string(), "blue",
        "class id " + std::to_string(int(mx)) + " is not a Cityscapes train id (< 20)");
  return seg;
}

void writeCachedSegmentation(const fs::path& file, const Segmentation& seg) {
  const cv::Mat zero(seg.classes.size(), CV_8UC1, cv::Scalar(0));
  cv::Mat img;
  cv::merge(std::vector<cv::Mat>{seg.classes, seg.confidence, zero}, img);
  std::vector<uchar> png;
  if (!cv::imencode(".png", img, png)) throw IoError(file.string(), "cannot encode the PNG");
  io::writeBytesAtomic(file, std::string(png.begin(), png.end()));
}

}  // namespace mapfuse::vehicle
