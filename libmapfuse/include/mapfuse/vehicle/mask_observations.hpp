#pragma once
/// @file The ground observations of a simulate frames drive from its semantic mask PNGs
/// (docs/lsm-build.md, semantics = masks): each mask's components (observationsFromMask), and
/// aerial boxes only from observations.jsonl when the drive has it.
#include <filesystem>
#include <vector>

#include "mapfuse/core/drive_records.hpp"
#include "mapfuse/io/drive_frames.hpp"

namespace mapfuse::vehicle {

/// @brief One FrameObservations per frame of `drive` (index, stamp, ground from its mask of
/// `width` x `height` px, components under `min_area` px dropped), frame-parallel; the first bad
/// mask stops the work and is rethrown with its type. `drive_dir` names the drive in errors.
/// @throws ParseError for a frame without a mask file; IoError / ParseError for a bad mask.
std::vector<FrameObservations> observationsFromMaskFiles(const io::DriveFrames& drive,
                                                         const std::filesystem::path& drive_dir,
                                                         int width, int height, int min_area);

}  // namespace mapfuse::vehicle
