#include "mapfuse/vehicle/aerial_colour.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

namespace mapfuse::vehicle {

double horizonRow(double u, const Eigen::Matrix3d& K, const Eigen::Vector3d& n) {
  if (std::abs(n.y()) < 1e-9) return std::numeric_limits<double>::infinity();
  // n . ((u - cx) / fx, (v - cy) / fy, 1) = 0
  return K(1, 2) - K(1, 1) * (n.x() * (u - K(0, 2)) / K(0, 0) + n.z()) / n.y();
}

std::vector<AerialObservation> detectColourCues(const cv::Mat& bgr, const Eigen::Matrix3d& K,
                                                const Eigen::Vector3d& n,
                                                const ColourCueSettings& s) {
  std::vector<AerialObservation> out;
  if (!s.enabled) return out;
  CV_Assert(bgr.type() == CV_8UC3);
  // Only the part above the horizon (plus the margin) can hold a cue: convert that band only.
  const double h_row = std::min(horizonRow(0, K, n), horizonRow(bgr.cols - 1, K, n));
  const int rows = std::clamp(int(std::floor(h_row)) - s.horizon_margin, 0, bgr.rows);
  if (rows <= 0) return out;
  cv::Mat hsv;
  cv::cvtColor(bgr.rowRange(0, rows), hsv, cv::COLOR_BGR2HSV);
  cv::Mat ch[3];
  cv::split(hsv, ch);
  // Red wraps around hue 0 (OpenCV hue 0-180).
  const cv::Mat red =
      ((ch[0] <= 8) | (ch[0] >= 170)) & (ch[1] >= s.min_saturation) & (ch[2] >= s.min_value);
  const cv::Mat dark = ch[2] < s.lamp_dark_value;
  cv::Mat labels, stats, centroids;
  const int count = cv::connectedComponentsWithStats(red, labels, stats, centroids, 8, CV_32S);
  const cv::Rect image(0, 0, bgr.cols, rows);
  for (int k = 1; k < count; ++k) {
    const int x = stats.at<int>(k, cv::CC_STAT_LEFT), y = stats.at<int>(k, cv::CC_STAT_TOP);
    const int w = stats.at<int>(k, cv::CC_STAT_WIDTH), h = stats.at<int>(k, cv::CC_STAT_HEIGHT);
    const int area = stats.at<int>(k, cv::CC_STAT_AREA);
    const double bottom_margin = horizonRow(x + 0.5 * w, K, n) - (y + h);
    if (bottom_margin < s.horizon_margin) continue;
    // Prohibition sign: a red ring; its lower part may be hidden, so the width is the diameter.
    if (w >= s.ring_min_diameter && w <= s.ring_max_diameter && h >= s.ring_min_visible * w &&
        h <= 1.4 * w && area <= s.ring_max_fill * w * h) {
      const double cu = x + 0.5 * (w - 1), cv_ = y + 0.5 * (w - 1), r = 0.42 * w;
      constexpr int kArc = 19;  // samples over the upper half-circle, 10 degrees apart
      int on = 0;
      for (int t = 0; t < kArc; ++t) {
        const double a = M_PI + t * M_PI / (kArc - 1);
        const int u = int(std::lround(cu + r * std::cos(a))),
                  v = int(std::lround(cv_ + r * std::sin(a)));
        if (image.contains({u, v}) && labels.at<int>(v, u) == k) ++on;
      }
      if (on >= s.ring_min_arc * kArc) {
        AerialObservation o;
        o.cls = CrowdClass::kTrafficSign;
        o.box = Eigen::Vector4d(x - 0.5, y - 0.5, x + w - 0.5, y + w - 0.5);
        o.points = {Eigen::Vector2d(cu, cv_)};
        o.confidence = double(on) / kArc;
        o.detector = 1;
        out.push_back(std::move(o));
        continue;
      }
    }
    // Lit lamp: a small bright red blob in a dark housing.
    if (area < s.lamp_min_area || w > s.lamp_max_side || h > s.lamp_max_side || w < 2 || h < 2 ||
        std::max(w, h) > 2 * std::min(w, h))
      continue;
    double peak = 0;
    cv::minMaxLoc(ch[2](cv::Rect(x, y, w, h)), nullptr, &peak, nullptr, nullptr,
                  labels(cv::Rect(x, y, w, h)) == k);
    if (peak < s.lamp_min_peak) continue;
    const cv::Rect around = cv::Rect(x - w, y - h, 3 * w, 3 * h) & image;
    const int dark_px = cv::countNonZero(dark(around));
    const double dark_share = double(dark_px) / std::max(1, around.area() - area);
    if (dark_share < s.lamp_min_dark_share) continue;
    AerialObservation o;
    o.cls = CrowdClass::kTrafficLight;
    o.box = Eigen::Vector4d(x - 0.5, y - 0.5, x + w - 0.5, y + h - 0.5);
    o.points = {Eigen::Vector2d(centroids.at<double>(k, 0), centroids.at<double>(k, 1))};
    o.confidence = std::min(1.0, dark_share);
    o.detector = 1;
    out.push_back(std::move(o));
  }
  return out;
}

}  // namespace mapfuse::vehicle
