// localize at the frames level (docs/localize.md "Frames level"): a raw drive read as lsm-build
// reads it, its markings ranged frame by frame (eq. 1), and the per-frame observations.
#include "mapfuse/cli/params.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/stages/localize.hpp"
#include "mapfuse/stages/lsm_build.hpp"

namespace mapfuse::stages {

localize::DriveObservations frameLevelObservations(const LocalizeInputs& in, const Lsm& lsm,
                                                   const LocalizeParams& params) {
  LsmBuildParams build;
  if (!in.lsm_build_config.empty()) paramsFromFile(build, in.lsm_build_config);
  LsmBuildInputs drive_in;
  drive_in.drive = std::filesystem::path(in.frames_dir) / lsm.drive_id;
  if (!std::filesystem::exists(drive_in.drive / "frames.json"))
    throw IoError(drive_in.drive.string(), "raw drive of '" + lsm.drive_id + "' not found");
  const LoadedDrive drive = loadDrive(drive_in, build);
  vehicle::LsmBuildResult planes;
  vehicle::calibrateGroundPlanes(drive, build.build, planes);
  const auto markings = vehicle::rangeMarkings(drive, planes.planes, build.build.ranging);
  return localize::frameObservationsOf(drive, markings, lsm, params.frames,
                                       params.localize.match_attributes, drive_in.drive.string());
}

}  // namespace mapfuse::stages
