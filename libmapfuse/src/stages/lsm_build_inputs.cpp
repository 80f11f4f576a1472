#include "mapfuse/stages/lsm_build_inputs.hpp"

#include <atomic>
#include <chrono>
#include <exception>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/core/paths.hpp"
#include "mapfuse/core/progress.hpp"
#include "mapfuse/geo/oxts.hpp"
#include "mapfuse/io/camera_calib.hpp"
#include "mapfuse/io/drive_frames.hpp"
#include "mapfuse/io/kitti_raw.hpp"
#include "mapfuse/vehicle/dead_reckoning.hpp"
#include "mapfuse/vehicle/fallback_perception.hpp"
#include "mapfuse/vehicle/flow_association.hpp"

namespace mapfuse::stages {
namespace fs = std::filesystem;
namespace {

void loadFramesLayout(const LsmBuildInputs& in, const LsmBuildParams& p, LoadedDrive& d) {
  io::DriveFrames df = io::readDriveFrames(in.drive);
  d.drive_id = in.drive_id.empty() ? df.drive_id : in.drive_id;
  d.vehicle_id = df.vehicle_id;
  d.calib = df.calib;
  d.gps = df.gps;
  for (const auto& f : df.frames) d.stamps.push_back(f.stamp);

  // Ego-motion.
  d.egomotion = p.egomotion == "auto" ? (in.poses.empty() ? "imu_wheel" : "poses") : p.egomotion;
  if (d.egomotion == "imu_wheel") {
    vehicle::DeadReckoningSettings s;
    s.wheel_scale = p.wheel_scale;
    s.gyro_bias = Eigen::Vector3d(p.gyro_bias_x, p.gyro_bias_y, p.gyro_bias_z);
    d.T_odom_body = vehicle::deadReckon(df.imu, df.wheel, d.stamps, s);
  } else if (d.egomotion != "poses") {
    throw ConfigError("LsmBuildParams::egomotion = \"" + d.egomotion +
                      "\". Violated constraint: a frames folder supports imu_wheel or poses");
  }

  // Semantics.
  d.semantics = p.semantics;
  if (d.semantics == "auto") d.semantics = df.observations.empty() ? "masks" : "observations";
  if (d.semantics == "observations") {
    if (df.observations.empty())
      throw InputError(in.drive.string() + ": semantics = observations but no observations file");
    d.frames = std::move(df.observations);
  } else if (d.semantics == "masks") {
    d.frames.resize(df.frames.size());
    std::vector<std::exception_ptr> errors(df.frames.size());
    Progress progress("masks", df.frames.size());
    std::atomic<bool> failed{false};
#pragma omp parallel for schedule(dynamic)
    for (int i = 0; i < int(df.frames.size()); ++i) {
      if (failed) continue;  // a bad mask stops the work early
      try {
        if (df.frames[i].mask.empty())
          throw ParseError((in.drive / "frames.csv").string(), "frame " + std::to_string(i),
                           "no mask file named");
        const cv::Mat mask = io::readMask(df.frames[i].mask, d.calib.width, d.calib.height);
        d.frames[i].index = df.frames[i].index;
        d.frames[i].stamp = df.frames[i].stamp;
        d.frames[i].ground = io::observationsFromMask(mask, p.mask_min_area);
        // Aerial boxes come only from observations.jsonl.
        if (!df.observations.empty()) d.frames[i].aerial = df.observations[i].aerial;
      } catch (...) {
        errors[i] = std::current_exception();
        failed = true;
      }
      progress.advance();
    }
    // Rethrow the first failure with its original type.
    for (const auto& e : errors)
      if (e) std::rethrow_exception(e);
  } else {
    throw ConfigError("LsmBuildParams::semantics = \"" + d.semantics +
                      "\". Violated constraint: a frames folder supports observations or masks");
  }
}

/// Poses file rows and drive frames must agree; checked before any network work.
void checkPoseCount(const LsmBuildInputs& in, std::size_t poses, std::size_t frames) {
  if (poses != frames)
    throw InputError(in.poses.string() + " has " + std::to_string(poses) +
                     " poses but the drive has " + std::to_string(frames) + " frames");
}

void loadKittiLayout(const LsmBuildInputs& in, const LsmBuildParams& p, LoadedDrive& d,
                     const std::vector<Pose3>& file_poses) {
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
  if (d.egomotion == "oxts") {
    if (!kd.has_oxts)
      throw InputError(in.drive.string() + ": egomotion = oxts but no OXTS records");
    std::vector<geo::OxtsRecord> rec;
    for (const auto& f : kd.frames) rec.push_back(io::readOxts(f));
    const double scale = geo::mercatorScale(rec.front().lat);
    const Pose3 T0_inv = geo::oxtsToMercatorPose(rec.front(), scale).inverse();
    for (const auto& r : rec) d.T_odom_body.push_back(T0_inv * geo::oxtsToMercatorPose(r, scale));
    for (std::size_t i = 0; i < rec.size(); ++i) {
      GpsFix g;
      g.stamp = d.stamps[i];
      g.position = {rec[i].lat, rec[i].lon, rec[i].alt};
      g.sigma_h = std::max(0.1, rec[i].pos_accuracy);
      g.sigma_v = 2.0 * g.sigma_h;
      d.gps.push_back(g);
    }
  } else if (d.egomotion != "poses") {
    throw ConfigError("LsmBuildParams::egomotion = \"" + d.egomotion +
                      "\". Violated constraint: a KITTI raw drive supports poses or oxts");
  } else {
    if (in.poses.empty()) throw InputError("egomotion = poses needs a poses file (--poses)");
    checkPoseCount(in, file_poses.size(), d.stamps.size());
  }
  d.semantics = p.semantics == "auto" ? "segmenter" : p.semantics;
  if (d.semantics != "segmenter")
    throw ConfigError("LsmBuildParams::semantics = \"" + d.semantics +
                      "\". Violated constraint: a KITTI raw drive needs the segmenter");
  fs::path model =
      p.model.empty() ? sharedRoot() / "models/enet-cityscapes/enet-model.net" : fs::path(p.model);
  vehicle::RoadSegmenter segmenter(model);
  d.frames.resize(d.images.size());
  Progress progress("frames", d.images.size());
  // The network uses OpenCV's own threads; frames run one after the other.
  for (std::size_t i = 0; i < d.images.size(); ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    const cv::Mat bgr = vehicle::readColorImage(d.images[i]);
    const cv::Mat road = segmenter.roadMask(bgr);
    const auto t1 = std::chrono::steady_clock::now();
    const auto lanes = vehicle::detectLanes(bgr, road, d.calib, vehicle::LaneDetectSettings{});
    const auto t2 = std::chrono::steady_clock::now();
    d.frames[i].index = int(i);
    d.frames[i].stamp = d.stamps[i];
    d.frames[i].ground = lanes.lanes;
    d.bev_images.push_back(lanes.bev_gray);
    d.network_seconds += std::chrono::duration<double>(t1 - t0).count();
    d.perception_seconds += std::chrono::duration<double>(t2 - t0).count();
    progress.advance();
  }
}

}  // namespace

LoadedDrive loadDrive(const LsmBuildInputs& in, const LsmBuildParams& p) {
  if (!fs::is_directory(in.drive)) throw IoError(in.drive.string(), "no such drive folder");
  LoadedDrive d;
  // The poses file is read and checked (rows, rotations) before any image or network work.
  const std::vector<Pose3> file_poses =
      in.poses.empty() ? std::vector<Pose3>{} : io::readKittiPoses(in.poses);
  d.input_kind = p.input_kind;
  if (d.input_kind == "auto")
    d.input_kind = fs::exists(in.drive / "frames.json") ? "frames"
                   : fs::exists(in.drive / "image_02")  ? "kitti_raw"
                                                        : "";
  if (d.input_kind == "frames")
    loadFramesLayout(in, p, d);
  else if (d.input_kind == "kitti_raw")
    loadKittiLayout(in, p, d, file_poses);
  else
    throw InputError(in.drive.string() +
                     ": neither a frames folder (frames.json) nor a KITTI raw drive (image_02)");

  if (d.egomotion == "poses") {
    if (in.poses.empty()) throw InputError("egomotion = poses needs a poses file (--poses)");
    auto T_world_cam0 = file_poses;
    if (p.poses_frame == "velo") {
      // Velodyne poses (lidar-semantic-map poses_velo.txt) are T_world_velo:
      // T_world_cam0 = T_world_velo * T_cam0_velo^-1 with T_cam0_velo = R_rect_00 T_velo_to_cam.
      if (!d.calib.has_velo)
        throw ConfigError(
            "LsmBuildParams::poses_frame = \"velo\". Violated constraint: "
            "needs a KITTI raw drive (Velodyne calibration)");
      const Pose3 T_velo_cam0 = d.calib.T_posecam_velo.inverse();
      for (Pose3& T : T_world_cam0) T = T * T_velo_cam0;
    }
    checkPoseCount(in, T_world_cam0.size(), d.stamps.size());
    // KITTI poses are of (rectified) camera 0; ours is camera 2 shifted by the baseline.
    const Pose3 T_cam0_cam = d.calib.T_cam_posecam.inverse();
    const Pose3 T_cam_body = d.calib.T_body_cam.inverse();
    const Pose3 T_first = (T_world_cam0.front() * T_cam0_cam * T_cam_body).inverse();
    for (const auto& T : T_world_cam0)
      d.T_odom_body.push_back(T_first * T * T_cam0_cam * T_cam_body);
  }
  // Aerial boxes without track ids: associate them frame to frame by optical flow.
  bool need_flow = false;
  for (const auto& f : d.frames)
    for (const auto& a : f.aerial) need_flow = need_flow || a.track_id < 0;
  if (need_flow && d.images.size() == d.frames.size()) {
    int64_t next_id = 0;
    cv::Mat prev;
    for (std::size_t i = 0; i < d.frames.size(); ++i) {
      cv::Mat gray;
      cv::cvtColor(vehicle::readColorImage(d.images[i]), gray, cv::COLOR_BGR2GRAY);
      if (prev.empty()) {
        for (auto& a : d.frames[i].aerial) a.track_id = next_id++;
      } else {
        vehicle::associateByFlow(prev, gray, d.frames[i - 1].aerial, d.frames[i].aerial, next_id,
                                 vehicle::FlowSettings{});
      }
      prev = gray;
    }
  } else if (need_flow) {
    MAPFUSE_WARN("lsm-build: aerial boxes without track ids and no images: they are ignored");
  }
  if (d.T_odom_body.size() != d.stamps.size() || d.frames.size() != d.stamps.size())
    throw InputError(in.drive.string() + ": frame counts disagree (poses " +
                     std::to_string(d.T_odom_body.size()) + ", semantics " +
                     std::to_string(d.frames.size()) + ", stamps " +
                     std::to_string(d.stamps.size()) + ")");
  return d;
}

}  // namespace mapfuse::stages
