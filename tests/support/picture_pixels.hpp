#pragma once
/// @file Pixel counts of a colour in pictures the tools draw (tests of map.png and the keys).
#include <array>
#include <cstdint>
#include <opencv2/core.hpp>

namespace mapfuse::test {

/// @brief How many pixels of `area` in a BGR picture have exactly the colour `rgb`.
inline int pixelsOf(const cv::Mat& bgr, const cv::Rect& area, const std::array<uint8_t, 3>& rgb) {
  int n = 0;
  for (int r = area.y; r < area.y + area.height; ++r)
    for (int c = area.x; c < area.x + area.width; ++c) {
      const cv::Vec3b p = bgr.at<cv::Vec3b>(r, c);
      n += p[2] == rgb[0] && p[1] == rgb[1] && p[0] == rgb[2];
    }
  return n;
}

}  // namespace mapfuse::test
