#pragma once
/// @file Stage `localize` (Song et al. 2023 §5, Fig. 12): localises georeferenced drives (LSMs) on
/// a vector map with localize::localizeDrive; with true trajectories, scores the lateral,
/// longitudinal and heading errors. Writes <drive>.trajectory.json per drive, with truth
/// <drive>.errors.csv and <drive>.errors.png, localize.config.json and localize.summary.json
/// (docs/localize.md).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "mapfuse/localize/drive_smoother.hpp"
#include "mapfuse/localize/frame_observations.hpp"
#include "mapfuse/localize/localizer.hpp"
#include "mapfuse/localize/map_frame.hpp"
#include "mapfuse/localize/truth_errors.hpp"

namespace mapfuse::stages {

struct LocalizeParams {
  static constexpr const char* kName = "LocalizeParams";
  localize::LocalizeSettings localize;
  localize::SmootherSettings smoother;
  localize::FrameLevelSettings frames;
  localize::LostMapSettings lost;

  template <class V>
  void visit(V& v) {
    localize.visit(v);
    smoother.visit(v);
    frames.visit(v);
    lost.visit(v);
  }
};

struct LocalizeInputs {
  std::string map;                 ///< vector map (aggregate's map, or simulate's truth map)
  std::vector<std::string> lsms;   ///< georeferenced LSMs, one drive each
  std::string truth_trajectories;  ///< folder of <drive>.trajectory.json (optional)
  std::string truth_map;           ///< truth vector map: errors in the map's frame (optional)
  /// Frames level: folder of raw drives (<drive_id>/frames.json, simulate --level frames); the
  /// LSMs are then lsm-build's of these drives, georeferenced. Empty: LSM level.
  std::string frames_dir;
  std::string lsm_build_config;  ///< frames level: lsm-build.config.json the LSMs were built with
};

struct LocalizedDrive {
  std::string file;
  std::string drive_id;
  localize::LocalizeResult result;
  std::optional<localize::LocalizeErrors> errors;    ///< with truth only
  std::optional<localize::MapToTruth> map_to_truth;  ///< with a truth map only
};

struct LocalizeRun {
  std::string level = "lsm";  ///< lsm | frames
  std::string solve;          ///< per_keyframe | full_drive
  std::vector<LocalizedDrive> drives;
  std::size_t keyframes = 0;
  std::size_t lost = 0;
  double seconds_localize = 0.0;  ///< summed localisation time (one core)
  double lostShare() const { return keyframes ? double(lost) / double(keyframes) : 1.0; }
};

/// @brief Frames level: the raw drive of `lsm` (inputs.frames_dir / drive id) read as lsm-build
/// reads it (inputs.lsm_build_config, else lsm-build's defaults), its ground markings ranged
/// frame by frame (eq. 1) and localize::frameObservationsOf.
/// @throws IoError when the drive folder is missing; InputError, ParseError, ConfigError.
localize::DriveObservations frameLevelObservations(const LocalizeInputs& inputs, const Lsm& lsm,
                                                   const LocalizeParams& params);

/// @brief The summary localize.summary.json holds.
nlohmann::json toJson(const LocalizeRun& run);

/// @brief Localises every drive, scores it when truth is given and writes the outputs.
/// @throws InputError (exit 3) when a drive is not georeferenced or the map was lost on more
/// than max_lost_share of the keyframes (outputs untouched); IoError, ParseError, ConfigError.
LocalizeRun runLocalize(const LocalizeInputs& inputs, const std::filesystem::path& out_dir,
                        const LocalizeParams& params);

}  // namespace mapfuse::stages
