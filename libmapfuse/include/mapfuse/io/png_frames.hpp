#pragma once
/// @file PNG writing for the tools that write a picture per frame or per drive (simulate,
/// lsm-build, lidar-semantic-map, the KITTI raw writer, semantic label images): OpenCV's encoder,
/// 5-15 times faster than io::writePng on camera frames and label masks (png_writer.hpp says why
/// the map-only tools avoid it).
#include <filesystem>
#include <opencv2/core.hpp>

namespace mapfuse::io {

/// @brief Encodes `image` (any type cv::imencode takes for PNG: 8/16-bit, 1/3/4 channels) and
/// writes it atomically to `path`. @throws IoError naming `path` when encoding or writing fails.
void writePngFrame(const std::filesystem::path& path, const cv::Mat& image);

}  // namespace mapfuse::io
