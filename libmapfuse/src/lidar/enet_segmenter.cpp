#include "mapfuse/lidar/enet_segmenter.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/dnn.hpp>
#include <opencv2/imgproc.hpp>

#include "mapfuse/core/classes.hpp"
#include "mapfuse/core/error.hpp"

namespace mapfuse::lidar {

struct EnetSegmenter::Impl {
  cv::dnn::Net net;
};

/// The image is reflect-padded to a multiple of this (px): ENet halves it three times on the way
/// down and its decoder unpools to the encoder's sizes, which must therefore halve exactly; 16 is
/// what the e-lab release was run with (../shared/data README: native scale, reflect padding to a
/// multiple of 16). A property of the network, not a tunable.
constexpr int kPadMultiple = 16;

EnetSegmenter::EnetSegmenter(const std::filesystem::path& model, const EnetSettings& settings)
    : impl_(std::make_unique<Impl>()), settings_(settings) {
  if (!std::filesystem::is_regular_file(model)) throw IoError(model.string(), "model not found");
  if (!(settings.scale > 0.1 && settings.scale <= 4.0))
    throw ConfigError("ENet scale must be in (0.1, 4]");
  try {
    impl_->net = cv::dnn::readNetFromTorch(model.string());
  } catch (const cv::Exception& e) {
    throw ParseError(model.string(), "", std::string("OpenCV cannot load the model: ") + e.what());
  }
  if (impl_->net.empty()) throw ParseError(model.string(), "", "OpenCV loaded an empty network");
  if (settings.threads > 0) cv::setNumThreads(settings.threads);  // process-wide (TBB arena)
  impl_->net.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);
  impl_->net.setPreferableTarget(cv::dnn::DNN_TARGET_CPU);
}

EnetSegmenter::~EnetSegmenter() = default;

io::SemanticImage EnetSegmenter::segment(const cv::Mat& bgr) {
  if (bgr.empty() || bgr.type() != CV_8UC3) throw InputError("ENet needs an 8-bit BGR image");
  const int W = bgr.cols, H = bgr.rows;
  cv::Mat scaled = bgr;
  if (settings_.scale != 1.0)
    cv::resize(bgr, scaled, cv::Size(), settings_.scale, settings_.scale, cv::INTER_LINEAR);
  const int m = kPadMultiple;
  const int pw = (scaled.cols + m - 1) / m * m, ph = (scaled.rows + m - 1) / m * m;
  cv::Mat padded;
  cv::copyMakeBorder(scaled, padded, 0, ph - scaled.rows, 0, pw - scaled.cols,
                     cv::BORDER_REFLECT_101);
  const cv::Mat blob = cv::dnn::blobFromImage(padded, 1.0 / 255.0, padded.size(), cv::Scalar(),
                                              /*swapRB=*/true, /*crop=*/false);
  impl_->net.setInput(blob);
  const cv::Mat out = impl_->net.forward();  // 1 x C x h x w scores
  if (out.dims != 4 || out.size[1] != kNumCityscapesClasses)
    throw InputError("ENet output has an unexpected shape (expected 20 channels)");
  const int oh = out.size[2], ow = out.size[3];
  const int C = kNumCityscapesClasses;
  // Per-pixel softmax and aggregation into the 8 LiDAR classes at the output resolution.
  std::vector<cv::Mat> agg(kNumLidarClasses);
  for (auto& a : agg) a = cv::Mat::zeros(oh, ow, CV_32F);
  const float* scores = out.ptr<float>();
  const std::size_t plane = static_cast<std::size_t>(oh) * ow;
  int lidar_of[kNumCityscapesClasses];
  for (int c = 0; c < C; ++c) lidar_of[c] = static_cast<int>(lidarClassFromCityscapes(c));
  for (std::size_t i = 0; i < plane; ++i) {
    float mx = -1e30f;
    for (int c = 0; c < C; ++c) mx = std::max(mx, scores[c * plane + i]);
    float e[kNumCityscapesClasses], sum = 0.f;
    for (int c = 0; c < C; ++c) sum += (e[c] = std::exp(scores[c * plane + i] - mx));
    const float inv = 1.0f / sum;
    for (int c = 0; c < C; ++c) agg[lidar_of[c]].ptr<float>()[i] += e[c] * inv;
  }
  // Crop the padding (in output resolution) and bring back to the native size.
  const double sx = static_cast<double>(ow) / pw, sy = static_cast<double>(oh) / ph;
  const cv::Rect roi(0, 0, std::max(1, static_cast<int>(std::lround(scaled.cols * sx))),
                     std::max(1, static_cast<int>(std::lround(scaled.rows * sy))));
  std::vector<cv::Mat> native(kNumLidarClasses);
  for (int k = 0; k < kNumLidarClasses; ++k) {
    if (roi.width == W && roi.height == H)
      native[k] = agg[k](roi);
    else
      cv::resize(agg[k](roi), native[k], cv::Size(W, H), 0, 0, cv::INTER_LINEAR);
  }
  std::vector<uint8_t> data(static_cast<std::size_t>(W) * H * kNumLidarClasses);
  for (int v = 0; v < H; ++v)
    for (int k = 0; k < kNumLidarClasses; ++k) {
      const float* row = native[k].ptr<float>(v);
      for (int u = 0; u < W; ++u)
        data[(static_cast<std::size_t>(v) * W + u) * kNumLidarClasses + k] =
            static_cast<uint8_t>(std::lround(std::clamp(row[u], 0.f, 1.f) * 255.f));
    }
  return io::SemanticImage::fromProbabilities(W, H, std::move(data));
}

}  // namespace mapfuse::lidar
