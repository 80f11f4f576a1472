#pragma once
/// @file ENet (Paszke et al. 2016, Cityscapes, Torch7 format) through OpenCV DNN, producing the
/// 8-class probability images of the semantics format: the image is scaled (native or 1.5x),
/// reflect-padded right/bottom to a multiple of 16, fed as RGB / 255; a per-pixel softmax over
/// the 20 Cityscapes outputs is aggregated into the 8 LiDAR classes (sum of the probabilities of
/// the Cityscapes classes that map to the same label, core/classes.hpp lidarClassFromCityscapes).
#include <filesystem>
#include <memory>
#include <opencv2/core.hpp>

#include "mapfuse/core/param.hpp"
#include "mapfuse/io/semantic_image.hpp"

namespace mapfuse::lidar {

struct EnetSettings {
  double scale = 1.0;  ///< input scale (1.0 native; 1.5 also works; never stretch the aspect)
  int threads = 0;     ///< cv::setNumThreads for the network; 0 = OpenCV's default (cores)

  template <class V>
  void visit(V& v) {
    v("enet_scale", scale, "", "ENet input scale (1.0 native, 1.5 also fine)",
      param::gt(0.1) & param::le(4));
    v("enet_threads", threads, "", "OpenCV threads of the network (0 = one per core)",
      param::in(0, 256));
  }
};

class EnetSegmenter {
 public:
  /// @brief Loads the Torch7 model. @throws IoError when missing, ParseError when OpenCV
  /// cannot read it.
  EnetSegmenter(const std::filesystem::path& model, const EnetSettings& settings);
  ~EnetSegmenter();
  EnetSegmenter(const EnetSegmenter&) = delete;
  EnetSegmenter& operator=(const EnetSegmenter&) = delete;

  /// @brief Segments one BGR 8-bit image into an 8-channel probability image of the same size.
  io::SemanticImage segment(const cv::Mat& bgr);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  EnetSettings settings_;
};

}  // namespace mapfuse::lidar
