#pragma once
/// @file Where a frame's class evidence comes from: precomputed images in the semantics format
/// (`<drive>/semantics_02` or another folder), or ENet run on image_02 with its output cached
/// in the same format so that re-runs skip the network.
#include <filesystem>
#include <memory>
#include <string>

#include "mapfuse/io/kitti_raw.hpp"
#include "mapfuse/io/semantic_image.hpp"
#include "mapfuse/lidar/enet_segmenter.hpp"

namespace mapfuse::lidar {

struct FrameSemanticsSettings {
  std::string segmenter =
      "auto";  ///< "auto" (precomputed when present, else enet), "enet", "precomputed"
  std::filesystem::path model;  ///< ENet Torch7 file
  EnetSettings enet;
  std::filesystem::path precomputed_dir;  ///< empty = <drive>/semantics_02
  std::filesystem::path cache_dir;        ///< ENet cache; empty = no cache
};

class FrameSemantics {
 public:
  /// @throws ConfigError for an unknown segmenter; IoError when "precomputed" has no folder.
  FrameSemantics(const io::KittiRawDrive& drive, const FrameSemanticsSettings& settings);
  ~FrameSemantics();

  /// @brief Class evidence of one frame.
  /// @throws IoError when the precomputed file or the image is missing; ParseError when bad.
  io::SemanticImage get(const io::KittiRawFrame& frame);

  const std::string& source() const { return source_; }  ///< "precomputed" or "enet"
  int fromPrecomputed() const { return n_pre_; }
  int fromCache() const { return n_cache_; }
  int fromNetwork() const { return n_net_; }
  double networkSeconds() const { return t_net_; }

 private:
  FrameSemanticsSettings s_;
  std::filesystem::path pre_dir_;
  std::string source_;
  std::unique_ptr<EnetSegmenter> enet_;
  int n_pre_ = 0, n_cache_ = 0, n_net_ = 0;
  double t_net_ = 0;
};

}  // namespace mapfuse::lidar
