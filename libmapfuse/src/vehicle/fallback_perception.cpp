#include "mapfuse/vehicle/fallback_perception.hpp"

#include <algorithm>
#include <chrono>
#include <opencv2/dnn.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "centerline.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/core/progress.hpp"
#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/png_decode.hpp"
#include "segmentation_cache.hpp"

namespace mapfuse::vehicle {

cv::Mat readColorImage(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path)) throw IoError(path.string(), "image missing");
  return io::decodePng(io::readBytes(path), path.string(), cv::IMREAD_COLOR);
}

struct RoadSegmenter::Impl {
  cv::dnn::Net net;
};

RoadSegmenter::RoadSegmenter(const std::filesystem::path& model) : impl_(new Impl) {
  if (!std::filesystem::exists(model))
    throw IoError(model.string(), "segmentation model missing (see docs/lsm-build.md)");
  try {
    impl_->net = cv::dnn::readNetFromTorch(model.string());
  } catch (const cv::Exception& e) {
    throw IoError(model.string(), std::string("cannot load the Torch model: ") + e.what());
  }
  if (impl_->net.empty()) throw IoError(model.string(), "cannot load the Torch model");
}

RoadSegmenter::~RoadSegmenter() = default;

Segmentation RoadSegmenter::segment(const cv::Mat& bgr) {
  // Native scale, reflect padding to a multiple of 16 (data/README.md).
  const int pw = (16 - bgr.cols % 16) % 16, ph = (16 - bgr.rows % 16) % 16;
  cv::Mat padded;
  cv::copyMakeBorder(bgr, padded, 0, ph, 0, pw, cv::BORDER_REFLECT_101);
  const cv::Mat blob = cv::dnn::blobFromImage(padded, 1.0 / 255.0, padded.size(), cv::Scalar(),
                                              /*swapRB=*/true, /*crop=*/false);
  impl_->net.setInput(blob);
  const cv::Mat out = impl_->net.forward();  // 1 x C x H x W
  const int C = out.size[1], H = out.size[2], W = out.size[3];
  cv::Mat cls(H, W, CV_8UC1, cv::Scalar(0));
  cv::Mat best(H, W, CV_32F, cv::Scalar(-1e30f));
  for (int c = 0; c < C; ++c) {
    const cv::Mat score(H, W, CV_32F, const_cast<float*>(out.ptr<float>(0, c)));
    const cv::Mat better = score > best;
    score.copyTo(best, better);
    cls.setTo(c, better);
  }
  // Softmax probability of the winning class: 1 / sum_c exp(s_c - s_max).
  cv::Mat sum(H, W, CV_32F, cv::Scalar(0)), e;
  for (int c = 0; c < C; ++c) {
    const cv::Mat score(H, W, CV_32F, const_cast<float*>(out.ptr<float>(0, c)));
    cv::exp(score - best, e);
    sum += e;
  }
  cv::Mat conf;
  cv::divide(255.0, sum, conf, 1.0, CV_8U);
  if (H != padded.rows || W != padded.cols) {
    cv::resize(cls, cls, padded.size(), 0, 0, cv::INTER_NEAREST);
    cv::resize(conf, conf, padded.size(), 0, 0, cv::INTER_LINEAR);
  }
  const cv::Rect roi(0, 0, bgr.cols, bgr.rows);
  return {cls(roi).clone(), conf(roi).clone()};
}

cv::Mat RoadSegmenter::classify(const cv::Mat& bgr) {
  return segment(bgr).classes;
}

cv::Mat RoadSegmenter::roadMask(const cv::Mat& bgr) {
  return (classify(bgr) == 1);
}

namespace {

/// Point on the ground plane `forward` m ahead and `left` m to the left, camera frame.
struct PlaneBasis {
  Eigen::Vector3d foot, fwd, left;
  explicit PlaneBasis(const GroundPlane& g) {
    const Eigen::Vector3d n = g.normal_cam.normalized();
    foot = -g.height * n;
    fwd = (Eigen::Vector3d::UnitZ() - n.z() * n).normalized();
    left = n.cross(fwd);
  }
  Eigen::Vector3d at(double f, double l) const { return foot + f * fwd + l * left; }
};

}  // namespace

LaneDetection detectLanes(const cv::Mat& bgr, const cv::Mat& road_mask, const CameraCalib& calib,
                          const LaneDetectSettings& s, const cv::Mat& road_users) {
  LaneDetection det;
  const PlaneBasis basis(calib.ground);
  const int rows = int(std::round((s.bev_max_x - s.bev_min_x) / s.bev_resolution));
  const int cols = int(std::round(2.0 * s.bev_half_width / s.bev_resolution));
  auto cellToGround = [&](double r, double c) {
    return Eigen::Vector2d(s.bev_max_x - r * s.bev_resolution,
                           s.bev_half_width - c * s.bev_resolution);
  };
  cv::Mat map_x(rows, cols, CV_32F), map_y(rows, cols, CV_32F);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const Eigen::Vector2d g = cellToGround(r, c);
      const auto px = projectPoint(calib.K, basis.at(g.x(), g.y()));
      map_x.at<float>(r, c) = px ? float(px->x()) : -1.f;
      map_y.at<float>(r, c) = px ? float(px->y()) : -1.f;
    }
  cv::Mat gray;
  cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
  cv::remap(gray, det.bev_gray, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_CONSTANT, 0);
  cv::remap(road_mask, det.bev_road, map_x, map_y, cv::INTER_NEAREST, cv::BORDER_CONSTANT, 0);
  cv::Mat bev_users;  // road users in the BEV: no markings there, and 0 = unseen in the mosaic
  if (!road_users.empty())
    cv::remap(road_users, bev_users, map_x, map_y, cv::INTER_NEAREST, cv::BORDER_CONSTANT, 0);

  // White top-hat with a horizontal element: bright ridges narrower than tophat_width.
  const int k = std::max(3, int(std::round(s.tophat_width / s.bev_resolution)) | 1);
  cv::Mat tophat;
  cv::morphologyEx(det.bev_gray, tophat, cv::MORPH_TOPHAT,
                   cv::getStructuringElement(cv::MORPH_RECT, {k, 1}));
  cv::Mat road;
  const int m = std::max(1, int(std::round(s.road_margin / s.bev_resolution)));
  cv::dilate(det.bev_road, road, cv::getStructuringElement(cv::MORPH_RECT, {2 * m + 1, 1}));
  cv::Scalar mean, stddev;
  cv::meanStdDev(tophat, mean, stddev, road);
  const double thr = std::max(s.min_contrast, mean[0] + s.contrast_sigmas * stddev[0]);
  det.bev_markings = (tophat > thr) & (road > 0);
  if (!bev_users.empty()) {
    det.bev_markings.setTo(0, bev_users);
    const cv::Mat unseen = det.bev_gray == 0;  // outside the image (remap's border)
    cv::max(det.bev_gray, 1, det.bev_gray);    // 0 is reserved for "not seen"
    det.bev_gray.setTo(0, bev_users | unseen);
  }
  // Close small breaks along the driving direction, then drop speckles.
  cv::morphologyEx(det.bev_markings, det.bev_markings, cv::MORPH_CLOSE,
                   cv::getStructuringElement(cv::MORPH_RECT, {1, 5}));
  cv::morphologyEx(det.bev_markings, det.bev_markings, cv::MORPH_OPEN,
                   cv::getStructuringElement(cv::MORPH_RECT, {1, 5}));

  const int step = std::max(1, int(std::round(s.sample_step / s.bev_resolution)));
  cv::Mat ids = det.bev_markings / 255;
  for (auto& comp : extractComponents(ids, 1, ThinMode::kRows, 10, step)) {
    const double length = comp.box.height * s.bev_resolution;
    const double width = comp.area * s.bev_resolution / std::max(1, comp.box.height);
    if (length < s.min_length || width > s.max_width || comp.pixels.size() < 2) continue;
    GroundObservation obs;
    obs.cls = CrowdClass::kLaneLine;
    std::vector<Eigen::Vector2d> ground;
    for (const auto& p : comp.pixels) {
      const Eigen::Vector2d g = cellToGround(p.y(), p.x());
      ground.push_back(g);
      if (auto px = projectPoint(calib.K, basis.at(g.x(), g.y()))) obs.pixels.push_back(*px);
    }
    if (obs.pixels.size() < 2) continue;
    det.lanes.push_back(std::move(obs));
    det.lanes_ground.push_back(std::move(ground));
  }
  // Solid / dashed from the marking profile along each line; gaps count only on visible road.
  const cv::Mat seen = (det.bev_gray > 0) & (road > 0);
  det.styles = classifyLineStyles(det.lanes_ground, det.bev_markings, seen,
                                  {s.bev_max_x, s.bev_half_width, s.bev_resolution}, s.style);
  for (std::size_t i = 0; i < det.lanes.size(); ++i)
    det.lanes[i].attributes.style = det.styles[i].style;
  return det;
}

LanePerception perceiveFrames(const std::vector<std::filesystem::path>& images,
                              const std::vector<double>& stamps, const CameraCalib& calib,
                              const std::filesystem::path& model, const PerceptionSettings& s) {
  using Clock = std::chrono::steady_clock;
  std::unique_ptr<RoadSegmenter> segmenter;  // loaded on the first frame not in the cache
  LanePerception out;
  LaneDetectSettings lane_settings;
  lane_settings.style = s.line_style;
  std::vector<double> periods;
  out.frames.resize(images.size());
  Progress progress("frames", images.size());
  for (std::size_t i = 0; i < images.size(); ++i) {
    const auto t0 = Clock::now();
    const cv::Mat bgr = readColorImage(images[i]);
    const std::filesystem::path cache =
        s.segmentation_cache.empty() ? std::filesystem::path()
                                     : segmentationCachePath(s.segmentation_cache, images[i]);
    std::optional<Segmentation> seg;
    if (!cache.empty()) seg = readCachedSegmentation(cache, bgr.size());
    if (seg) {
      ++out.cached_frames;
    } else {
      if (!segmenter) segmenter = std::make_unique<RoadSegmenter>(model);
      seg = segmenter->segment(bgr);
      if (!cache.empty()) writeCachedSegmentation(cache, *seg);
    }
    const auto t1 = Clock::now();
    const cv::Mat users = roadUserMask(seg->classes, s.road_user_margin);
    const auto lanes =
        detectLanes(bgr, seg->classes == cityscapes::kRoad, calib, lane_settings, users);
    for (const auto& st : lanes.styles) {
      out.lane_styles.solid += st.style == LineStyle::kSolid ? 1 : 0;
      out.lane_styles.dashed += st.style == LineStyle::kDashed ? 1 : 0;
      out.lane_styles.untyped += st.style == LineStyle::kNone ? 1 : 0;
      if (st.period > 0) periods.push_back(st.period);
    }
    out.frames[i].index = int(i);
    out.frames[i].stamp = stamps[i];
    out.frames[i].ground = lanes.lanes;
    out.frames[i].aerial = detectAerial(seg->classes, seg->confidence, s.aerial);
    setPoleAxisKeyPoints(out.frames[i].aerial, calib.K, calib.ground.normal_cam.normalized());
    for (auto& a : detectColourCues(bgr, calib.K, calib.ground.normal_cam.normalized(), s.colour))
      out.frames[i].aerial.push_back(std::move(a));
    out.aerial_detections += int(out.frames[i].aerial.size());
    out.bev_images.push_back(lanes.bev_gray);
    const auto t2 = Clock::now();
    out.network_seconds += std::chrono::duration<double>(t1 - t0).count();
    out.seconds += std::chrono::duration<double>(t2 - t0).count();
    progress.advance();
  }
  if (!periods.empty()) {
    std::nth_element(periods.begin(), periods.begin() + long(periods.size() / 2), periods.end());
    out.lane_styles.dash_period = periods[periods.size() / 2];
  }
  return out;
}

}  // namespace mapfuse::vehicle
