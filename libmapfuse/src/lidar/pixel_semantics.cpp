#include "mapfuse/lidar/pixel_semantics.hpp"

#include <algorithm>

namespace mapfuse::lidar {

ClassDistribution pixelDistribution(const io::SemanticImage& img, int u, int v,
                                    const PixelSemanticsSettings& s) {
  ClassDistribution d;
  const float confidence = static_cast<float>(s.label_confidence);  // computed in float
  const float floor = static_cast<float>(s.min_probability);
  if (img.isLabels()) {
    const float rest = (1.0f - confidence) / (kNumLidarClasses - 1);
    d.fill(rest);
    d[img.label(u, v)] = confidence;
  } else {
    const uint8_t* p = img.prob(u, v);
    for (int c = 0; c < kNumLidarClasses; ++c) d[c] = p[c] * (1.0f / 255.0f);
  }
  float sum = 0.f;
  for (float& x : d) {
    x = std::max(x, floor);
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
