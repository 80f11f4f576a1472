#pragma once
/// @file Solid / dashed typing of real lane-line pieces (issue 21) in the bird's-eye view (BEV)
/// of one frame. The pieces (one per marking component, fallback_perception.hpp) that lie on one
/// straight painted line are chained; the marking mask is read along the chain's fitted line
/// (the marking profile), split into marked runs and gaps, and only what the camera saw counts:
/// a gap is evidence of a dashed line when all of it is visible road (not a road user, inside
/// the image) and it lies between two marked runs; a marked run longer than any dash is evidence
/// of a solid line. Anything else stays untyped (LineStyle::kNone). The dash period of a dashed
/// line is its mean dash + gap length.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "mapfuse/core/classes.hpp"
#include "mapfuse/core/param.hpp"

namespace mapfuse::vehicle {

/// Thresholds of the typing; declared once, in visit().
struct LineStyleSettings {
  bool enabled = true;             ///< type lane-line pieces as solid or dashed
  double chain_lateral = 0.3;      ///< m, pieces this close to one fitted line are one line
  double probe_half_width = 0.15;  ///< m, lateral reach of the profile around the fitted line
  double min_gap = 1.5;            ///< m, a seen gap at least this long between two dashes
  double max_dash = 7.0;           ///< m, a marked run longer than this is not a dash
  double min_solid = 10.0;         ///< m, a marked run at least this long is a solid line

  template <class V>
  void visit(V& v) {
    using namespace param;
    v("line_style", enabled, "",
      "type real lane lines solid or dashed from the marking profile along each line");
    v("style_chain_lateral", chain_lateral, "m",
      "lane pieces this close to one fitted line are one painted line", gt(0) & le(10));
    v("style_probe_half_width", probe_half_width, "m",
      "lateral reach of the marking profile around the fitted line", gt(0) & le(10));
    v("dash_min_gap", min_gap, "m",
      "a fully visible gap at least this long between two marked runs makes the line dashed",
      gt(0) & le(100));
    v("dash_max_length", max_dash, "m", "marked runs longer than this are not dashes",
      gt(0) & le(100));
    v("solid_min_length", min_solid, "m", "a marked run at least this long makes the line solid",
      gt(0) & le(1000));
    v.relation("solid_min_length", min_solid, min_solid > max_dash, "> dash_max_length");
  }
};

/// Geometry of a BEV image: row 0 is `max_forward`, column 0 is `half_width` to the left.
struct BevGrid {
  double max_forward = 30.0;  ///< m, forward distance of row 0
  double half_width = 10.0;   ///< m, left offset of column 0
  double resolution = 0.05;   ///< m per pixel
};

/// The style of one lane-line piece and the profile evidence behind it.
struct PieceStyle {
  LineStyle style = LineStyle::kNone;
  int line = -1;        ///< index of the chained painted line in this frame
  double run = 0.0;     ///< m, length of the marked run holding the piece
  double period = 0.0;  ///< m, dashed: mean dash + gap of its line; else 0
};

/// @brief Types every piece (a polyline of (forward, left) m on the ground plane) from the BEV
/// marking mask `markings` (CV_8U, 255 = marking) and `seen` (CV_8U, 255 = visible road).
/// @return one PieceStyle per piece, in order
std::vector<PieceStyle> classifyLineStyles(const std::vector<std::vector<Eigen::Vector2d>>& pieces,
                                           const cv::Mat& markings, const cv::Mat& seen,
                                           const BevGrid& grid, const LineStyleSettings& settings);

}  // namespace mapfuse::vehicle
