#include "centerline.hpp"

#include <opencv2/imgproc.hpp>

namespace mapfuse::vehicle {

std::vector<MaskComponent> extractComponents(const cv::Mat& mask, int class_id, ThinMode mode,
                                             int min_area, int step) {
  CV_Assert(mask.type() == CV_8UC1);
  step = std::max(1, step);
  cv::Mat binary = (mask == class_id);
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(binary, labels, stats, centroids, 8, CV_32S);
  std::vector<MaskComponent> out;
  for (int c = 1; c < n; ++c) {
    const int area = stats.at<int>(c, cv::CC_STAT_AREA);
    if (area < min_area) continue;
    MaskComponent comp;
    comp.area = area;
    comp.box = cv::Rect(stats.at<int>(c, cv::CC_STAT_LEFT), stats.at<int>(c, cv::CC_STAT_TOP),
                        stats.at<int>(c, cv::CC_STAT_WIDTH), stats.at<int>(c, cv::CC_STAT_HEIGHT));
    const cv::Rect& b = comp.box;
    if (mode == ThinMode::kHull) {
      std::vector<cv::Point> pts, hull;
      for (int y = b.y; y < b.y + b.height; ++y) {
        const int* row = labels.ptr<int>(y);
        for (int x = b.x; x < b.x + b.width; ++x)
          if (row[x] == c) pts.emplace_back(x, y);
      }
      cv::convexHull(pts, hull);
      for (const auto& p : hull) comp.pixels.emplace_back(p.x, p.y);
    } else if (mode == ThinMode::kRows) {
      // Bottom (near) to top (far); pixel centres at integer coordinates.
      for (int y = b.y + b.height - 1; y >= b.y; y -= step) {
        const int* row = labels.ptr<int>(y);
        double sum = 0.0;
        int cnt = 0;
        for (int x = b.x; x < b.x + b.width; ++x)
          if (row[x] == c) sum += x, ++cnt;
        if (cnt) comp.pixels.emplace_back(sum / cnt, y);
      }
    } else {
      for (int x = b.x; x < b.x + b.width; x += step) {
        double sum = 0.0;
        int cnt = 0;
        for (int y = b.y; y < b.y + b.height; ++y)
          if (labels.at<int>(y, x) == c) sum += y, ++cnt;
        if (cnt) comp.pixels.emplace_back(x, sum / cnt);
      }
    }
    if (!comp.pixels.empty()) out.push_back(std::move(comp));
  }
  return out;
}

std::vector<GroundObservation> observationsFromMask(const cv::Mat& mask, int min_area) {
  std::vector<GroundObservation> out;
  for (int id = 1; id <= 4; ++id) {
    const CrowdClass cls = CrowdClass(id - 1);
    const ThinMode mode = cls == CrowdClass::kLaneLine   ? ThinMode::kRows
                          : cls == CrowdClass::kStopLine ? ThinMode::kColumns
                                                         : ThinMode::kHull;
    for (auto& comp : extractComponents(mask, id, mode, min_area)) {
      GroundObservation o;
      o.cls = cls;
      o.pixels = std::move(comp.pixels);
      out.push_back(std::move(o));
    }
  }
  return out;
}

}  // namespace mapfuse::vehicle
