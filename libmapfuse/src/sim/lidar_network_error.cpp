#include "mapfuse/sim/lidar_network_error.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include <opencv2/imgproc.hpp>

#include "mapfuse/core/classes.hpp"

namespace mapfuse::sim {
namespace {

/// Smooth random field in [0, 1) of the image size: uniform values on a coarse grid of cell
/// `scale` px, bilinearly upsampled and rank-equalised so that P(field < a) ~= a.
cv::Mat smoothField(int w, int h, double scale, std::mt19937_64& rng) {
  const int gw = std::max(2, static_cast<int>(w / scale) + 2);
  const int gh = std::max(2, static_cast<int>(h / scale) + 2);
  cv::Mat coarse(gh, gw, CV_32F);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  for (int y = 0; y < gh; ++y)
    for (int x = 0; x < gw; ++x) coarse.at<float>(y, x) = u(rng);
  cv::Mat field;
  cv::resize(coarse, field, cv::Size(w, h), 0, 0, cv::INTER_CUBIC);
  // Rank equalisation through a 256-bin histogram.
  std::vector<double> hist(257, 0.0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      hist[static_cast<std::size_t>(std::clamp(field.at<float>(y, x), 0.f, 1.f) * 255.f) + 1] += 1;
  for (std::size_t i = 1; i < hist.size(); ++i) hist[i] += hist[i - 1];
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const auto b = static_cast<std::size_t>(std::clamp(field.at<float>(y, x), 0.f, 1.f) * 255.f);
      field.at<float>(y, x) = static_cast<float>(hist[b] / hist.back());
    }
  return field;
}

void confuse(cv::Mat& labels, LidarClass from, LidarClass to, double share, double scale,
             std::mt19937_64& rng) {
  const cv::Mat field = smoothField(labels.cols, labels.rows, scale, rng);
  if (share <= 0.0) return;
  for (int y = 0; y < labels.rows; ++y)
    for (int x = 0; x < labels.cols; ++x)
      if (labels.at<uint8_t>(y, x) == static_cast<uint8_t>(from) && field.at<float>(y, x) < share)
        labels.at<uint8_t>(y, x) = static_cast<uint8_t>(to);
}

}  // namespace

std::vector<uint8_t> corruptLabels(const CameraFrame& truth, const NetworkErrorParams& p,
                                   uint64_t seed) {
  std::mt19937_64 rng(seed);
  const int w = truth.width, h = truth.height;
  cv::Mat src(h, w, CV_8U, const_cast<uint8_t*>(truth.labels.data()));
  // 1. Calibration offset: the network's labels are shifted against the true projection.
  cv::Mat labels;
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, p.offset_u, 0, 1, p.offset_v);
  cv::warpAffine(src, labels, shift, src.size(), cv::INTER_NEAREST, cv::BORDER_REPLICATE);
  // 2. Region-level confusion of similar classes.
  confuse(labels, LidarClass::kSidewalk, LidarClass::kRoad, p.sidewalk_as_road, p.confusion_scale,
          rng);
  confuse(labels, LidarClass::kRoad, LidarClass::kSidewalk, p.road_as_sidewalk, p.confusion_scale,
          rng);
  confuse(labels, LidarClass::kFence, LidarClass::kBuilding, p.fence_as_building, p.confusion_scale,
          rng);
  confuse(labels, LidarClass::kBuilding, LidarClass::kFence, p.building_as_fence, p.confusion_scale,
          rng);
  // 3. Wrong-class blobs (irregular: a few overlapping ellipses) over labelled pixels.
  std::poisson_distribution<int> count(p.blobs_per_frame);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  const int blobs = p.blobs_per_frame > 0.0 ? count(rng) : 0;
  for (int k = 0; k < blobs; ++k) {
    // Draws in a fixed order (sim/draw_order.hpp): the order the release (gcc) build used.
    const double cy = u01(rng), cx = u01(rng);
    const cv::Point c(static_cast<int>(cx * w), static_cast<int>(h * (0.3 + 0.7 * cy)));
    const double r = p.blob_radius_min + (p.blob_radius_max - p.blob_radius_min) * u01(rng);
    const uint8_t cls = static_cast<uint8_t>(1 + static_cast<int>(u01(rng) * 6.999));
    cv::Mat mask = cv::Mat::zeros(h, w, CV_8U);
    for (int e = 0; e < 3; ++e) {
      const double ey = u01(rng), ex = u01(rng);
      const cv::Point ce(c.x + static_cast<int>((ex - 0.5) * r),
                         c.y + static_cast<int>((ey - 0.5) * r));
      const double angle = u01(rng), minor = u01(rng), major = u01(rng);
      cv::ellipse(
          mask, ce,
          cv::Size(static_cast<int>(r * (0.5 + major)), static_cast<int>(r * (0.3 + 0.5 * minor))),
          angle * 180.0, 0, 360, cv::Scalar(255), cv::FILLED);
    }
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        if (mask.at<uint8_t>(y, x) && labels.at<uint8_t>(y, x) != 0) labels.at<uint8_t>(y, x) = cls;
  }
  return std::vector<uint8_t>(labels.begin<uint8_t>(), labels.end<uint8_t>());
}

io::SemanticImage networkProbabilities(const CameraFrame& truth, const NetworkErrorParams& p,
                                       uint64_t seed) {
  const int w = truth.width, h = truth.height;
  const std::vector<uint8_t> hard = corruptLabels(truth, p, seed);
  // 4. Boundary bleeding: Gaussian-softened one-hot maps, then the confidence floor.
  std::vector<cv::Mat> soft(kNumLidarClasses);
  for (int c = 0; c < kNumLidarClasses; ++c) {
    soft[c] = cv::Mat::zeros(h, w, CV_32F);
    for (int i = 0; i < w * h; ++i)
      if (hard[static_cast<std::size_t>(i)] == c) soft[c].at<float>(i / w, i % w) = 1.f;
    if (p.bleed_sigma > 0.0) cv::GaussianBlur(soft[c], soft[c], cv::Size(0, 0), p.bleed_sigma);
  }
  std::vector<uint8_t> probs(static_cast<std::size_t>(w) * h * kNumLidarClasses);
  const double floor = (1.0 - p.confidence) / kNumLidarClasses;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double sum = 0.0;
      for (int c = 0; c < kNumLidarClasses; ++c) sum += soft[c].at<float>(y, x);
      const std::size_t base = (static_cast<std::size_t>(y) * w + x) * kNumLidarClasses;
      for (int c = 0; c < kNumLidarClasses; ++c) {
        const double q = p.confidence * soft[c].at<float>(y, x) / std::max(sum, 1e-9) + floor;
        probs[base + c] = static_cast<uint8_t>(std::lround(std::clamp(q, 0.0, 1.0) * 255.0));
      }
    }
  return io::SemanticImage::fromProbabilities(w, h, std::move(probs));
}

}  // namespace mapfuse::sim
