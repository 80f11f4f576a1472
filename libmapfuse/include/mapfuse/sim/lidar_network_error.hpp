#pragma once
/// @file Per-pixel class probabilities "as a segmentation network would give them", derived from
/// the true label image with realistic errors (docs/lidar-ground-truth.md): a small calibration
/// offset, confusion of similar classes in smooth regions (sidewalk -> road, road -> sidewalk,
/// fence -> building, building -> fence), wrong-class blobs, boundary bleeding (Gaussian
/// softening of the one-hot maps, which also swallows thin structures) and a confidence floor.
#include <cstdint>
#include <vector>

#include "mapfuse/core/param.hpp"
#include "mapfuse/io/semantic_image.hpp"
#include "mapfuse/sim/lidar_camera.hpp"

namespace mapfuse::sim {

struct NetworkErrorParams {
  double offset_u = 1.5;            ///< px, horizontal calibration offset of the labels
  double offset_v = 1.0;            ///< px, vertical calibration offset
  double sidewalk_as_road = 0.20;   ///< share of sidewalk area labelled road
  double road_as_sidewalk = 0.06;   ///< share of road area labelled sidewalk
  double fence_as_building = 0.25;  ///< share of fence area labelled building
  double building_as_fence = 0.05;  ///< share of building area labelled fence
  double confusion_scale = 120.0;   ///< px, size of the confused regions
  double blobs_per_frame = 4.0;     ///< mean number of wrong-class blobs
  double blob_radius_min = 10.0;    ///< px
  double blob_radius_max = 45.0;    ///< px
  double bleed_sigma = 2.0;         ///< px, Gaussian softening of class boundaries
  double confidence = 0.8;          ///< probability mass on the (softened) labels

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("offset_u", offset_u, "px", "horizontal calibration offset of the network labels",
      in(-1000, 1000));
    v("offset_v", offset_v, "px", "vertical calibration offset of the network labels",
      in(-1000, 1000));
    v("sidewalk_as_road", sidewalk_as_road, "", "share of sidewalk area the network calls road",
      in(0, 1));
    v("road_as_sidewalk", road_as_sidewalk, "", "share of road area the network calls sidewalk",
      in(0, 1));
    v("fence_as_building", fence_as_building, "", "share of fence area called building", in(0, 1));
    v("building_as_fence", building_as_fence, "", "share of building area called fence", in(0, 1));
    // the confusion field is drawn on a grid of image size / confusion_scale cells
    v("confusion_scale", confusion_scale, "px", "size of the confused regions", in(1, 1e6));
    v("blobs_per_frame", blobs_per_frame, "", "mean number of wrong-class blobs per image",
      in(0, 1000));
    v("blob_radius_min", blob_radius_min, "px", "smallest blob radius", gt(0) & le(10000));
    v("blob_radius_max", blob_radius_max, "px", "largest blob radius", gt(0) & le(10000));
    v.relation("blob_radius_min", blob_radius_min, blob_radius_min <= blob_radius_max,
               "<= blob_radius_max");
    v("bleed_sigma", bleed_sigma, "px", "Gaussian softening of class boundaries", in(0, 100));
    v("confidence", confidence, "", "probability mass on the network's labels (rest uniform)",
      gt(0) & le(1));
  }
};

/// @brief The corrupted hard labels before softening (for tests and the docs).
std::vector<uint8_t> corruptLabels(const CameraFrame& truth, const NetworkErrorParams& params,
                                   uint64_t seed);

/// @brief 8-channel probability image (io/semantic_image.hpp format) from the true labels.
/// Deterministic in (truth, params, seed).
io::SemanticImage networkProbabilities(const CameraFrame& truth, const NetworkErrorParams& params,
                                       uint64_t seed);

}  // namespace mapfuse::sim
