#pragma once
/// @file The fallback perception's segmentation cache (issue 21): one 3-channel PNG per image,
/// `<image stem>.seg.png`, blue = Cityscapes class id, green = its probability x 255, red = 0.
/// ENet takes ~0.5-1 s per KITTI frame; with the cache a rerun of lsm-build on the same images
/// (parameter studies) skips the network.
#include <filesystem>
#include <optional>

#include "mapfuse/vehicle/fallback_perception.hpp"

namespace mapfuse::vehicle {

/// @brief The cache file of `image` in `folder`.
std::filesystem::path segmentationCachePath(const std::filesystem::path& folder,
                                            const std::filesystem::path& image);

/// @brief The cached segmentation, nullopt when the file does not exist.
/// @throws ParseError when the file is undecodable, not 3-channel 8-bit, not `size`, or holds
/// a class id >= 20.
std::optional<Segmentation> readCachedSegmentation(const std::filesystem::path& file,
                                                   const cv::Size& size);

/// @brief Writes `seg` to `file` (atomic; staged with the run's outputs when a transaction is
/// open). @throws IoError.
void writeCachedSegmentation(const std::filesystem::path& file, const Segmentation& seg);

}  // namespace mapfuse::vehicle
