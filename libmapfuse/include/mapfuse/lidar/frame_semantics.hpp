#pragma once
/// @file Where a frame's class evidence comes from: precomputed images in the semantics format
/// (`<drive>/semantics_02` or another folder), or ENet run on image_02 with its output cached
/// in the same format so that re-runs skip the network.
#include <filesystem>
#include <memory>
#include <string>

#include "mapfuse/core/param.hpp"
#include "mapfuse/io/kitti_raw.hpp"
#include "mapfuse/io/semantic_image.hpp"
#include "mapfuse/lidar/enet_segmenter.hpp"

namespace mapfuse::lidar {

struct FrameSemanticsSettings {
  std::string segmenter =
      "auto";         ///< "auto" (precomputed when present, else enet), "enet", "precomputed"
  std::string model;  ///< ENet Torch7 file; empty = <shared>/models/enet-cityscapes/enet-model.net
  EnetSettings enet;
  std::string semantics_dir;  ///< precomputed folder; empty = <drive>/semantics_02
  bool cache = true;          ///< ENet outputs cached (in the folder the caller names)

  template <class V>
  void visit(V& v) {
    v("segmenter", segmenter, "",
      "auto|enet|precomputed (auto: precomputed when the folder has the first frame)",
      param::oneOf({"auto", "enet", "precomputed"}));
    v("model", model, "",
      "ENet Torch7 model (empty = <shared>/models/enet-cityscapes/enet-model.net)");
    enet.visit(v);
    v("semantics_dir", semantics_dir, "",
      "precomputed semantics folder (empty = <drive>/semantics_02)");
    v("cache_semantics", cache, "", "cache ENet outputs in <output>/semantics_02");
  }
};

class FrameSemantics {
 public:
  /// @param cache_dir where ENet outputs are cached when `settings.cache` (empty: nowhere)
  /// @throws ConfigError for an unknown segmenter; IoError when "precomputed" has no folder.
  FrameSemantics(const io::KittiRawDrive& drive, const FrameSemanticsSettings& settings,
                 const std::filesystem::path& cache_dir = {});
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
  std::filesystem::path cache_dir_;  ///< empty = no cache
  std::string source_;
  std::unique_ptr<EnetSegmenter> enet_;
  int n_pre_ = 0, n_cache_ = 0, n_net_ = 0;
  double t_net_ = 0;
};

}  // namespace mapfuse::lidar
