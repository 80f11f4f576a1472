#pragma once
/// @file PNG encoding with zlib alone. The tools that only write pictures (aggregate, evaluate,
/// stitch) use it instead of OpenCV's imgcodecs, whose Debian build links GDAL and ~140 shared
/// libraries: 0.12 s of dynamic loading at every start of a per-drive or per-tile job.
/// Tools that write PNGs per frame (simulate, lsm-build, lidar-semantic-map) use
/// io::writePngFrame (png_frames.hpp, cv::imencode):
/// this encoder tries every row filter and deflates at level 6, which suits one map picture but
/// is slow on photographic frames (1242x375 RGB: 182 ms vs OpenCV's 11 ms; a 1280x720 label
/// mask: 7 ms vs 2 ms, half the bytes).
#include <filesystem>
#include <opencv2/core.hpp>
#include <string>

namespace mapfuse::io {

/// @brief PNG bytes of an 8-bit image: CV_8UC1 (grey), CV_8UC3 (BGR, OpenCV's order) or CV_8UC4
/// (BGRA). Each row gets the PNG filter (None, Sub, Up, Average or Paeth) with the smallest sum of
/// absolute filtered bytes, then the image is deflated. @throws InputError on an empty image or
/// another type.
std::string encodePng(const cv::Mat& image);

/// @brief encodePng, written atomically to `path`. @throws IoError when the write fails.
void writePng(const std::filesystem::path& path, const cv::Mat& image);

}  // namespace mapfuse::io
