#pragma once
/// @file `simulate --level frames` (docs/formats-frames.md): per-drive folder with calibration,
/// IMU / wheel / GPS streams, per-frame ground-marking masks (PNG), pixel polylines and 2D boxes
/// of aerial elements with track ids and truth ids, and the true pose of every frame.
#include <filesystem>

#include "mapfuse/core/param.hpp"
#include "mapfuse/sim/drive.hpp"
#include "mapfuse/sim/lsm_observer.hpp"
#include "mapfuse/sim/sim_camera.hpp"
#include "mapfuse/sim/world.hpp"

namespace mapfuse::sim {

struct FramesParams {
  double pixel_sigma = 0.5;  ///< px, noise of pixel observations (0 = exact projections)
  bool masks = true;         ///< write masks/<index>.png

  template <class V>
  void visit(V& v) {
    v("frames_pixel_sigma", pixel_sigma, "px", "pixel noise of frame observations",
      param::in(0, 1000));
    v("frames_masks", masks, "", "write per-frame PNG masks");
  }
};

/// Counts of one written drive.
struct FramesStats {
  int frames = 0;
  int ground_observations = 0;
  int aerial_observations = 0;
};

/// @brief Writes frames/<drive_id>/ below `out_dir` for one drive.
FramesStats writeFramesDrive(const std::filesystem::path& drive_dir, const World& world,
                             const PieceIndex& index, const Drive& drive, const SimCamera& camera,
                             const DriveParams& drive_params, const FramesParams& params,
                             uint64_t seed);

}  // namespace mapfuse::sim
