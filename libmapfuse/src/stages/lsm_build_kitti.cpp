// lsm-build's KITTI raw layout: camera 2 images and calibration, OXTS ego-motion (or a poses
// file, read by loadDrive), lane lines and aerial boxes from the fallback perception.
#include <cmath>

#include "mapfuse/core/error.hpp"
#include "mapfuse/core/paths.hpp"
#include "mapfuse/io/camera_calib.hpp"
#include "mapfuse/io/kitti_raw.hpp"
#include "mapfuse/stages/lsm_build.hpp"
#include "mapfuse/vehicle/ego_motion.hpp"

namespace mapfuse::stages {
namespace fs = std::filesystem;

void refuseLsmBuildParam(const char* key, const std::string& value, const char* rule) {
  throw ConfigError(std::string(LsmBuildParams::kName) + "::" + key + " = \"" + value +
                    "\". Violated constraint: " + rule);
}

void refuseUnusedPoses(const LsmBuildInputs& in, const std::string& egomotion) {
  if (!in.poses.empty() && egomotion != "poses")
    throw ConfigError(in.poses.string() + ": a poses file is given (--poses) but " +
                      LsmBuildParams::kName + "::egomotion is \"" + egomotion +
                      "\" for this drive; use --egomotion poses to build from it");
}

void loadKittiRawDrive(const LsmBuildInputs& in, const LsmBuildParams& p, LoadedDrive& d) {
  const io::KittiRawDrive kd =
      io::openKittiRawDrive(in.drive, io::FrameRange{0, p.kitti_last_frame, 1});
  d.drive_id = in.drive_id.empty() ? in.drive.filename().string() : in.drive_id;
  if (d.drive_id.empty()) d.drive_id = in.drive.parent_path().filename().string();
  d.vehicle_id = "kitti";
  d.calib = io::readKittiCameraCalib(kd.date_dir, p.camera_height);
  for (const auto& f : kd.frames) {
    if (f.image.empty())
      throw IoError((in.drive / "image_02/data" / (f.name + ".png")).string(),
                    "camera image missing");
    d.images.push_back(f.image);
    d.stamps.push_back(std::isfinite(f.timestamp) ? f.timestamp : 0.1 * f.index);
  }
  d.egomotion = p.egomotion == "auto" ? (kd.has_oxts ? "oxts" : "poses") : p.egomotion;
  refuseUnusedPoses(in, d.egomotion);
  if (d.egomotion == "oxts") {
    if (!kd.has_oxts)
      throw InputError(in.drive.string() + ": egomotion = oxts but no OXTS records");
    std::vector<geo::OxtsRecord> records;
    for (const auto& f : kd.frames) records.push_back(io::readOxts(f));
    auto ego = vehicle::egoMotionFromOxts(records, d.stamps);
    d.T_odom_body = std::move(ego.T_odom_body);
    d.gps = std::move(ego.gps);
  } else if (d.egomotion == "poses") {
    loadPosesFile(in, p, d);  // before the network: a bad file fails at once
  } else {
    refuseLsmBuildParam("egomotion", d.egomotion, "a KITTI raw drive supports poses or oxts");
  }
  d.semantics = p.semantics == "auto" ? "segmenter" : p.semantics;
  if (d.semantics != "segmenter")
    refuseLsmBuildParam("semantics", d.semantics, "a KITTI raw drive needs the segmenter");
  const fs::path model = p.perception.model.empty()
                             ? sharedRoot() / "models/enet-cityscapes/enet-model.net"
                             : fs::path(p.perception.model);
  auto lanes = vehicle::perceiveFrames(d.images, d.stamps, d.calib, model, p.perception);
  d.frames = std::move(lanes.frames);
  d.bev_images = std::move(lanes.bev_images);
  d.perception_seconds = lanes.seconds;
  d.network_seconds = lanes.network_seconds;
  d.cached_frames = lanes.cached_frames;
  d.aerial_detections = lanes.aerial_detections;
  d.lane_styles = lanes.lane_styles;
}

}  // namespace mapfuse::stages
