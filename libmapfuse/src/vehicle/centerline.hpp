#pragma once
/// @file Thinning of ground-marking masks to pixel centre lines (Song et al. 2023 §3.2.2):
/// each connected component of a class is one instance (so every dash of a dashed line stays
/// its own segment); lane lines are thinned row by row (centroid of the component's pixels in
/// each image row), stop lines column by column, planar markings keep their convex hull.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "mapfuse/core/drive_records.hpp"

namespace mapfuse::vehicle {

/// How a mask component is reduced to pixels.
enum class ThinMode { kRows, kColumns, kHull };

/// One instance found in a mask.
struct MaskComponent {
  std::vector<Eigen::Vector2d> pixels;  ///< centre line (ordered) or hull, px
  int area = 0;                         ///< pixels in the component
  cv::Rect box;                         ///< bounding box, px
};

/// @brief Connected components (8-connected) of `mask == class_id`, each thinned per `mode`;
/// components smaller than `min_area` pixels are dropped.
/// @param mask CV_8UC1 class-id image.
std::vector<MaskComponent> extractComponents(const cv::Mat& mask, int class_id, ThinMode mode,
                                             int min_area, int step = 1);

/// @brief Ground observations of a mask: one per connected component of the classes 1-4
/// (CrowdClass + 1), lane lines thinned to centre lines, stop lines column-wise, planar hulls.
/// @param mask CV_8UC1 class-id image (docs/formats-frames.md "masks").
/// @param min_area px, smaller components are noise.
std::vector<GroundObservation> observationsFromMask(const cv::Mat& mask, int min_area);

}  // namespace mapfuse::vehicle
