#include "mapfuse/vehicle/flow_association.hpp"

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include "mapfuse/vehicle/fallback_perception.hpp"

namespace mapfuse::vehicle {

double boxIou(const Eigen::Vector4d& a, const Eigen::Vector4d& b) {
  const double w = std::min(a(2), b(2)) - std::max(a(0), b(0));
  const double h = std::min(a(3), b(3)) - std::max(a(1), b(1));
  if (w <= 0.0 || h <= 0.0) return 0.0;
  const double inter = w * h;
  const double area = (a(2) - a(0)) * (a(3) - a(1)) + (b(2) - b(0)) * (b(3) - b(1));
  return inter / std::max(1e-9, area - inter);
}

void associateByFlow(const cv::Mat& prev_gray, const cv::Mat& next_gray,
                     const std::vector<AerialObservation>& prev,
                     std::vector<AerialObservation>& next, int64_t& next_id, const FlowSettings& s,
                     std::vector<Eigen::Vector4d>* moved_boxes) {
  // Flow a grid of points per previous box; the median displacement moves the box.
  std::vector<Eigen::Vector4d> predicted(prev.size());
  std::vector<cv::Point2f> pts, moved;
  for (const auto& b : prev)
    for (int i = 0; i < s.grid; ++i)
      for (int j = 0; j < s.grid; ++j)
        pts.emplace_back(float(b.box(0) + (i + 0.5) * (b.box(2) - b.box(0)) / s.grid),
                         float(b.box(1) + (j + 0.5) * (b.box(3) - b.box(1)) / s.grid));
  std::vector<uchar> status;
  std::vector<float> err;
  if (!pts.empty())
    cv::calcOpticalFlowPyrLK(prev_gray, next_gray, pts, moved, status, err, {s.window, s.window},
                             s.pyramid_levels);
  const int per = s.grid * s.grid;
  for (std::size_t k = 0; k < prev.size(); ++k) {
    std::vector<float> dx, dy;
    for (int q = 0; q < per; ++q)
      if (status[k * per + q]) {
        dx.push_back(moved[k * per + q].x - pts[k * per + q].x);
        dy.push_back(moved[k * per + q].y - pts[k * per + q].y);
      }
    if (dx.empty()) {
      predicted[k] = prev[k].box;
      continue;
    }
    std::nth_element(dx.begin(), dx.begin() + dx.size() / 2, dx.end());
    std::nth_element(dy.begin(), dy.begin() + dy.size() / 2, dy.end());
    const Eigen::Vector4d d(dx[dx.size() / 2], dy[dy.size() / 2], dx[dx.size() / 2],
                            dy[dy.size() / 2]);
    predicted[k] = prev[k].box + d;
  }
  // Greedy one-to-one matching by IoU (short sides widened to min_box_side), best pairs first.
  auto widen = [&](Eigen::Vector4d b) {
    for (int k = 0; k < 2; ++k) {
      const double side = b(k + 2) - b(k), grow = 0.5 * std::max(0.0, s.min_box_side - side);
      b(k) -= grow;
      b(k + 2) += grow;
    }
    return b;
  };
  struct Pair {
    double iou;
    std::size_t p, n;
  };
  std::vector<Pair> pairs;
  for (std::size_t p = 0; p < prev.size(); ++p)
    for (std::size_t n = 0; n < next.size(); ++n)
      if (prev[p].cls == next[n].cls && prev[p].detector == next[n].detector)
        if (const double iou = boxIou(widen(predicted[p]), widen(next[n].box)); iou >= s.min_iou)
          pairs.push_back({iou, p, n});
  std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) {
    return a.iou != b.iou ? a.iou > b.iou : (a.p != b.p ? a.p < b.p : a.n < b.n);
  });
  std::vector<bool> used_p(prev.size()), used_n(next.size());
  for (auto& n : next) n.track_id = -1;
  for (const auto& pr : pairs) {
    if (used_p[pr.p] || used_n[pr.n]) continue;
    used_p[pr.p] = used_n[pr.n] = true;
    next[pr.n].track_id = prev[pr.p].track_id;
  }
  for (auto& n : next)
    if (n.track_id < 0) n.track_id = next_id++;
  if (moved_boxes) *moved_boxes = predicted;
}

void associateAerialByFlow(const std::vector<std::filesystem::path>& images,
                           std::vector<FrameObservations>& frames, const FlowSettings& settings) {
  int64_t next_id = 0;
  cv::Mat prev;
  std::vector<AerialObservation> lost;  // tracks missed in the previous frame, box flowed on
  std::vector<int> lost_age;            // frames since each was last seen
  for (std::size_t i = 0; i < frames.size(); ++i) {
    cv::Mat gray;
    cv::cvtColor(readColorImage(images[i]), gray, cv::COLOR_BGR2GRAY);
    if (prev.empty()) {
      for (auto& a : frames[i].aerial) a.track_id = next_id++;
    } else {
      std::vector<AerialObservation> from = frames[i - 1].aerial;
      std::vector<int> age(from.size(), 0);
      from.insert(from.end(), lost.begin(), lost.end());
      age.insert(age.end(), lost_age.begin(), lost_age.end());
      std::vector<Eigen::Vector4d> moved;
      associateByFlow(prev, gray, from, frames[i].aerial, next_id, settings, &moved);
      lost.clear();
      lost_age.clear();
      for (std::size_t k = 0; k < from.size(); ++k) {
        bool continued = false;
        for (const auto& a : frames[i].aerial)
          continued = continued || a.track_id == from[k].track_id;
        if (continued || age[k] + 1 > settings.max_gap) continue;
        lost.push_back(from[k]);
        lost.back().box = moved[k];
        lost_age.push_back(age[k] + 1);
      }
    }
    prev = gray;
  }
}

}  // namespace mapfuse::vehicle
