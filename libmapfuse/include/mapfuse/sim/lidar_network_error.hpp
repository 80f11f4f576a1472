#pragma once
/// @file Per-pixel class probabilities "as a segmentation network would give them", derived from
/// the true label image with realistic errors (docs/lidar-ground-truth.md): a small calibration
/// offset, confusion of similar classes in smooth regions (sidewalk -> road, road -> sidewalk,
/// fence -> building, building -> fence), wrong-class blobs, boundary bleeding (Gaussian
/// softening of the one-hot maps, which also swallows thin structures) and a confidence floor.
#include <cstdint>
#include <vector>

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
};

/// @brief The corrupted hard labels before softening (for tests and the docs).
std::vector<uint8_t> corruptLabels(const CameraFrame& truth, const NetworkErrorParams& params,
                                   uint64_t seed);

/// @brief 8-channel probability image (io/semantic_image.hpp format) from the true labels.
/// Deterministic in (truth, params, seed).
io::SemanticImage networkProbabilities(const CameraFrame& truth, const NetworkErrorParams& params,
                                       uint64_t seed);

}  // namespace mapfuse::sim
