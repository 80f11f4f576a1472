#include "mapfuse/vehicle/aerial_detection.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace mapfuse::vehicle {

std::vector<AerialObservation> detectAerial(const cv::Mat& classes, const cv::Mat& confidence,
                                            const AerialDetectSettings& s) {
  std::vector<AerialObservation> out;
  if (!s.enabled) return out;
  CV_Assert(classes.type() == CV_8UC1 && confidence.type() == CV_8UC1 &&
            classes.size() == confidence.size());
  const std::pair<int, CrowdClass> kinds[] = {
      {cityscapes::kTrafficSign, CrowdClass::kTrafficSign},
      {cityscapes::kTrafficLight, CrowdClass::kTrafficLight},
      {cityscapes::kPole, CrowdClass::kPole}};
  // Road users (no margin), summed for the surroundings test of each component.
  cv::Mat users_sum;
  cv::integral(roadUserMask(classes, 0) / 255, users_sum, CV_32S);
  auto usersIn = [&](int x0, int y0, int x1, int y1) {  // x1, y1 exclusive, clamped
    x0 = std::clamp(x0, 0, classes.cols), x1 = std::clamp(x1, 0, classes.cols);
    y0 = std::clamp(y0, 0, classes.rows), y1 = std::clamp(y1, 0, classes.rows);
    return users_sum.at<int>(y1, x1) - users_sum.at<int>(y0, x1) - users_sum.at<int>(y1, x0) +
           users_sum.at<int>(y0, x0);
  };
  constexpr int kRing = 3;  // px
  for (const auto& [id, cls] : kinds) {
    const cv::Mat mask = classes == id;
    cv::Mat labels, stats, centroids;
    const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
    // Sum of the class probability per component, one pass over the image.
    std::vector<double> conf_sum(n, 0.0);
    for (int r = 0; r < labels.rows; ++r) {
      const int* l = labels.ptr<int>(r);
      const uint8_t* c = confidence.ptr<uint8_t>(r);
      for (int col = 0; col < labels.cols; ++col)
        if (l[col] > 0) conf_sum[l[col]] += c[col];
    }
    // Components as (box, area, probability sum); pole pieces one above the other merged.
    struct Blob {
      int x0, y0, x1, y1, area;  // px, x1 / y1 exclusive
      double conf_sum;
    };
    std::vector<Blob> blobs;
    for (int k = 1; k < n; ++k) {
      const int x = stats.at<int>(k, cv::CC_STAT_LEFT), y = stats.at<int>(k, cv::CC_STAT_TOP);
      blobs.push_back({x, y, x + stats.at<int>(k, cv::CC_STAT_WIDTH),
                       y + stats.at<int>(k, cv::CC_STAT_HEIGHT), stats.at<int>(k, cv::CC_STAT_AREA),
                       conf_sum[k]});
    }
    if (cls == CrowdClass::kPole) {
      for (bool merged = true; merged;) {
        merged = false;
        for (std::size_t i = 0; i < blobs.size() && !merged; ++i)
          for (std::size_t j = i + 1; j < blobs.size() && !merged; ++j) {
            Blob &a = blobs[i], &b = blobs[j];
            const bool columns = std::min(a.x1, b.x1) > std::max(a.x0, b.x0);
            const int gap = std::max(a.y0, b.y0) - std::min(a.y1, b.y1);
            if (!columns || gap > s.pole_merge_gap) continue;
            a = {std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1),
                 std::max(a.y1, b.y1), a.area + b.area,      a.conf_sum + b.conf_sum};
            blobs.erase(blobs.begin() + long(j));
            merged = true;
          }
      }
    }
    for (const Blob& b : blobs) {
      const int x = b.x0, y = b.y0, w = b.x1 - b.x0, h = b.y1 - b.y0, area = b.area;
      if (area < s.min_area) continue;
      if (x < s.border_margin || x + w > classes.cols - s.border_margin) continue;
      const double conf = b.conf_sum / (255.0 * area);
      const int ring_area = (w + 2 * kRing) * (h + 2 * kRing) - area;
      if (usersIn(x - kRing, y - kRing, x + w + kRing, y + h + kRing) >
          s.max_road_user_share * ring_area)
        continue;
      if (conf < s.min_confidence) continue;
      if (cls == CrowdClass::kPole && (h < s.min_pole_height || h < s.min_pole_elongation * w))
        continue;
      AerialObservation a;
      a.cls = cls;
      // Pixel centres at integer coordinates: the box spans the outer pixel edges.
      a.box = Eigen::Vector4d(x - 0.5, y - 0.5, x + w - 0.5, y + h - 0.5);
      a.confidence = conf;
      out.push_back(std::move(a));
    }
  }
  return out;
}

void setPoleAxisKeyPoints(std::vector<AerialObservation>& observations, const Eigen::Matrix3d& K,
                          const Eigen::Vector3d& n) {
  const double fx = K(0, 0), fy = K(1, 1), cx = K(0, 2), cy = K(1, 2);
  if (std::abs(n.y()) < 1e-9) return;  // the camera looks straight down or up: no horizon
  for (auto& a : observations) {
    if (a.cls != CrowdClass::kPole) continue;
    const double u = 0.5 * (a.box(0) + a.box(2));
    // n . ((u - cx) / fx, (v - cy) / fy, 1) = 0
    const double v = cy - fy * (n.x() * (u - cx) / fx + n.z()) / n.y();
    a.points = {Eigen::Vector2d(u, v)};
  }
}

cv::Mat roadUserMask(const cv::Mat& classes, int margin_px) {
  cv::Mat mask = (classes >= cityscapes::kPerson) & (classes <= cityscapes::kBicycle);
  if (margin_px > 0)
    cv::dilate(
        mask, mask,
        cv::getStructuringElement(cv::MORPH_ELLIPSE, {2 * margin_px + 1, 2 * margin_px + 1}));
  return mask;
}

}  // namespace mapfuse::vehicle
