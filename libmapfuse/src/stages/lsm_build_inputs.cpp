// lsm-build's input half: reads a drive into a LoadedDrive (calibration, stamps, ego-motion,
// semantics), whatever the layout; the KITTI raw layout is in lsm_build_kitti.cpp.
#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/io/drive_frames.hpp"
#include "mapfuse/stages/lsm_build.hpp"
#include "mapfuse/vehicle/ego_motion.hpp"
#include "mapfuse/vehicle/flow_association.hpp"
#include "mapfuse/vehicle/mask_observations.hpp"

namespace mapfuse::stages {
namespace fs = std::filesystem;
void loadPosesFile(const LsmBuildInputs& in, const LsmBuildParams& p, LoadedDrive& d) {
  if (in.poses.empty()) throw InputError("egomotion = poses needs a poses file (--poses)");
  const bool velo = p.poses_frame == "velo";
  if (velo && !d.calib.has_velo)
    refuseLsmBuildParam("poses_frame", "velo", "needs a KITTI raw drive (Velodyne calibration)");
  const auto poses = io::readKittiPoses(in.poses);  // rows and rotations checked
  if (poses.size() != d.stamps.size())
    throw InputError(in.poses.string() + " has " + std::to_string(poses.size()) +
                     " poses but the drive has " + std::to_string(d.stamps.size()) + " frames");
  d.T_odom_body = vehicle::bodyPosesFromPosesFile(poses, d.calib, velo);
}

void loadFramesDrive(const LsmBuildInputs& in, const LsmBuildParams& p, LoadedDrive& d) {
  io::DriveFrames df = io::readDriveFrames(in.drive);
  d.drive_id = in.drive_id.empty() ? df.drive_id : in.drive_id;
  d.vehicle_id = df.vehicle_id;
  d.calib = df.calib;
  d.gps = df.gps;
  for (const auto& f : df.frames) d.stamps.push_back(f.stamp);
  d.egomotion = p.egomotion == "auto" ? (in.poses.empty() ? "imu_wheel" : "poses") : p.egomotion;
  refuseUnusedPoses(in, d.egomotion);
  if (d.egomotion == "imu_wheel")
    d.T_odom_body = vehicle::deadReckon(df.imu, df.wheel, d.stamps, p.dead_reckoning);
  else if (d.egomotion == "poses")
    loadPosesFile(in, p, d);
  else
    refuseLsmBuildParam("egomotion", d.egomotion, "a frames folder supports imu_wheel or poses");
  d.semantics = p.semantics;
  if (d.semantics == "auto") d.semantics = df.observations.empty() ? "masks" : "observations";
  if (d.semantics == "observations") {
    if (df.observations.empty())
      throw InputError(in.drive.string() + ": semantics = observations but no observations file");
    d.frames = std::move(df.observations);
  } else if (d.semantics == "masks") {
    d.frames = vehicle::observationsFromMaskFiles(df, in.drive, d.calib.width, d.calib.height,
                                                  p.perception.mask_min_area);
  } else {
    refuseLsmBuildParam("semantics", d.semantics, "a frames folder supports observations or masks");
  }
}

LoadedDrive loadDrive(const LsmBuildInputs& in, const LsmBuildParams& p) {
  if (!fs::is_directory(in.drive)) throw IoError(in.drive.string(), "no such drive folder");
  LoadedDrive d;  // the poses file is read by the layouts (loadPosesFile), before the network
  d.input_kind = p.input_kind;
  if (d.input_kind == "auto")
    d.input_kind = fs::exists(in.drive / "frames.json") ? "frames"
                   : fs::exists(in.drive / "image_02")  ? "kitti_raw"
                                                        : "";
  if (d.input_kind == "frames")
    loadFramesDrive(in, p, d);
  else if (d.input_kind == "kitti_raw")
    loadKittiRawDrive(in, p, d);
  else
    throw InputError(in.drive.string() +
                     ": neither a frames folder (frames.json) nor a KITTI raw drive (image_02)");

  // Aerial boxes without track ids: associate them frame to frame by optical flow.
  bool need_flow = false;
  for (const auto& f : d.frames)
    for (const auto& a : f.aerial) need_flow = need_flow || a.track_id < 0;
  vehicle::FlowSettings flow;
  if (d.semantics == "segmenter") {
    flow.min_box_side = p.perception.track_min_box_side;
    flow.max_gap = p.perception.track_max_gap;
  }
  if (need_flow && d.images.size() == d.frames.size())
    vehicle::associateAerialByFlow(d.images, d.frames, flow);
  else if (need_flow)
    MAPFUSE_WARN("lsm-build: aerial boxes without track ids and no images: they are ignored");
  if (d.T_odom_body.size() != d.stamps.size() || d.frames.size() != d.stamps.size())
    throw InputError(in.drive.string() + ": frame counts disagree (poses " +
                     std::to_string(d.T_odom_body.size()) + ", semantics " +
                     std::to_string(d.frames.size()) + ", stamps " +
                     std::to_string(d.stamps.size()) + ")");
  return d;
}

}  // namespace mapfuse::stages
