#pragma once
/// @file The key of a top-down map picture (docs/formats.md "Pictures"): a panel appended on the
/// right of the picture with a legend (one swatch per class drawn, plus extra entries such as the
/// trajectory), a scale bar of a round length and a north arrow. The picture itself is not drawn
/// over: the panel widens the image, so no map pixel is hidden.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <opencv2/core.hpp>
#include <set>
#include <string>
#include <vector>

#include "mapfuse/core/classes.hpp"

namespace mapfuse::io {

/// One legend line: a swatch of `rgb` and its label.
struct LegendEntry {
  std::string label;
  std::array<uint8_t, 3> rgb{};  ///< R, G, B
  bool line = false;             ///< swatch drawn as a line (trajectories) instead of a box
};

/// What the key shows.
struct PictureKey {
  std::vector<LegendEntry> legend;
  double metres_per_pixel = 0.0;  ///< picture scale; 0 = no scale bar
  bool north_up = true;           ///< +y (north) points up in the picture: draw the arrow
  std::string title;              ///< optional first line(s), wrapped to the panel's width
  std::string up_note;            ///< without north: what points up (e.g. "up: car's left")
};

/// @brief `text` broken into lines of at most `max_width` px at `font_scale` (Hershey simplex),
/// at spaces, after '_' or '/', or anywhere inside a word longer than a line.
std::vector<std::string> wrapText(const std::string& text, double font_scale, int max_width);

/// @brief Legend lines of the crowd classes in `present`, in class order, in their map colours.
std::vector<LegendEntry> crowdLegend(const std::set<CrowdClass>& present);

/// @brief Legend lines of the LiDAR classes in `present`, in class order (SemanticKITTI colours).
std::vector<LegendEntry> lidarLegend(const std::set<LidarClass>& present);

/// @brief Draws `path` (map x/y, m) as a 2 px polyline of colour `rgb` into a north-up picture
/// whose top-left pixel corner is map (`top_left`.x, `top_left`.y), `metres_per_pixel` per pixel.
/// @return the number of path points inside the picture (0: nothing to put in the legend).
int drawPath(cv::Mat& bgr, const std::vector<Eigen::Vector3d>& path,
             const Eigen::Vector2d& top_left, double metres_per_pixel,
             const std::array<uint8_t, 3>& rgb);

/// @brief Length of the scale bar (m): the largest 1, 2 or 5 x 10^k not longer than
/// `max_pixels` at `metres_per_pixel` (at least 1 pixel long).
double scaleBarLength(double metres_per_pixel, int max_pixels);

/// @brief The picture `bgr` (CV_8UC3) with the key panel on its right (panel width 200 px, the
/// height grown when the legend needs more rows than the picture is tall). Every text line fits
/// the panel (titles wrap); without `north_up` no arrow, the `up_note` instead.
cv::Mat withPictureKey(const cv::Mat& bgr, const PictureKey& key);

}  // namespace mapfuse::io
