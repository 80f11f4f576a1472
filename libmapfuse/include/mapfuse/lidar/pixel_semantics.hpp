#pragma once
/// @file Per-pixel class distributions from a semantics image (label or probability image,
/// io/semantic_image.hpp) as measurement likelihoods P(z_t | l) for the voxel fusion.
#include "mapfuse/core/classes.hpp"
#include "mapfuse/core/param.hpp"
#include "mapfuse/io/semantic_image.hpp"
#include "mapfuse/lidar/voxel_map.hpp"

namespace mapfuse::lidar {

struct PixelSemanticsSettings {
  double label_confidence = 0.7;  ///< probability given to the label of a label image
  double min_probability = 0.02;  ///< floor of every class probability (then renormalised)

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("label_confidence", label_confidence, "", "probability given to the label of a label image",
      gt(1.0 / kNumLidarClasses) & le(1));
    v("min_probability", min_probability, "", "floor of every class probability of a measurement",
      gt(0) & lt(1.0 / kNumLidarClasses));
  }
};

/// @brief Distribution at pixel (u, v): a label image gives label_confidence to its label and
/// the rest spread evenly; a probability image gives value/255. Both are floored at
/// min_probability and renormalised, so no class is ever ruled out by one frame.
ClassDistribution pixelDistribution(const io::SemanticImage& img, int u, int v,
                                    const PixelSemanticsSettings& s);

/// @brief Argmax class of pixel (u, v).
uint8_t pixelLabel(const io::SemanticImage& img, int u, int v);

}  // namespace mapfuse::lidar
