#include "mapfuse/lidar/pixel_semantics.hpp"

#include <algorithm>

namespace mapfuse::lidar {

ClassDistribution pixelDistribution(const io::SemanticImage& img, int u, int v,
                                    const PixelSemanticsSettings& s) {
  ClassDistribution d;
  if (img.isLabels()) {
    const float rest = (1.0f - s.label_confidence) / (kNumLidarClasses - 1);
    d.fill(rest);
    d[img.label(u, v)] = s.label_confidence;
  } else {
    const uint8_t* p = img.prob(u, v);
    for (int c = 0; c < kNumLidarClasses; ++c) d[c] = p[c] * (1.0f / 255.0f);
  }
  float sum = 0.f;
  for (float& x : d) {
    x = std::max(x, s.min_probability);
    sum += x;
  }
  for (float& x : d) x /= sum;
  return d;
}

uint8_t pixelLabel(const io::SemanticImage& img, int u, int v) {
  if (img.isLabels()) return img.label(u, v);
  const uint8_t* p = img.prob(u, v);
  return static_cast<uint8_t>(std::max_element(p, p + img.channels) - p);
}

}  // namespace mapfuse::lidar
