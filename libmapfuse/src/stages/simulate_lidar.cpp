#include "mapfuse/stages/simulate_lidar.hpp"

#include <chrono>
#include <cstdio>

#include "mapfuse/cli/params.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/core/progress.hpp"
#include "mapfuse/io/kitti_calib.hpp"
#include "mapfuse/io/kitti_raw_writer.hpp"
#include "mapfuse/io/output_transaction.hpp"
#include "mapfuse/io/semantic_image.hpp"
#include "mapfuse/io/semantic_kitti.hpp"
#include "mapfuse/io/stage_report.hpp"
#include "mapfuse/io/velodyne.hpp"

namespace mapfuse::stages {
namespace {
namespace fs = std::filesystem;
constexpr const char* kStage = "simulate-lidar";

double seconds(std::chrono::steady_clock::time_point a) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count();
}

std::string poseLine(const Pose3& T) {
  std::string line;
  char buf[32];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) {
      std::snprintf(buf, sizeof(buf), "%.17g", T.matrix()(r, c));
      line += (line.empty() ? "" : " ") + std::string(buf);
    }
  return line;
}

/// The files of one frame: scan, labels, image, probabilities, true labels, OXTS.
void writeFrame(const fs::path& drive_dir, int k, const sim::LidarFrame& f, double dt,
                const io::MercatorAnchor& anchor) {
  const std::string name = io::kittiFrameName(k);
  io::VelodyneScan vs;
  vs.points.reserve(f.scan.points.size());
  vs.reflectance.reserve(f.scan.points.size());
  for (const auto& p : f.scan.points) {
    vs.points.emplace_back(p.head<3>());
    vs.reflectance.push_back(p.w());
  }
  const sim::CameraFrame& cam = f.camera;
  io::writeVelodyneBin(drive_dir / "velodyne_points" / "data" / (name + ".bin"), vs);
  io::writeSemanticKittiLabels(drive_dir / "labels" / (name + ".label"), f.scan.labels);
  io::writePngBgr(drive_dir / "image_02" / "data" / (name + ".png"), cam.width, cam.height,
                  sim::shadeLabels(cam));
  io::writeSemanticImage(io::semanticsDir(drive_dir) / (name + ".prob"), f.probabilities);
  io::writeSemanticImage(drive_dir / "ground_truth" / "label_02" / (name + ".png"),
                         io::SemanticImage::fromLabels(cam.width, cam.height, cam.labels));
  const geo::OxtsRecord rec = sim::oxtsRecord(f.T_world_imu, f.T_world_imu_next, dt, anchor);
  io::writeLines(drive_dir / "oxts" / "data" / (name + ".txt"), {io::formatOxtsLine(rec)});
}

}  // namespace

bool isKittiDate(const std::string& d) {
  return d.size() == 10 && d[4] == '_' && d[7] == '_';
}

nlohmann::json toJson(const SimulateLidarRun& run) {
  nlohmann::json classes = nlohmann::json::object();
  for (int c = 0; c < kNumLidarClasses; ++c)
    classes[lidarClassName(static_cast<LidarClass>(c))] = run.points.per_class[c];
  return {{"drive_dir", run.drive_dir.string()},
          {"frames", run.frames},
          {"road_length_m", run.road_length},
          {"primitives", run.primitives},
          {"moving_vehicles", run.moving_vehicles},
          {"points_per_scan",
           {{"mean", static_cast<double>(run.points.total) / run.frames},
            {"min", run.points.min},
            {"max", run.points.max}}},
          {"points_per_class", classes},
          {"moving_vehicle_points", run.points.moving_vehicle},
          {"timings_s",
           {{"lidar", run.seconds_lidar},
            {"camera_and_network", run.seconds_camera},
            {"write", run.seconds_write},
            {"total", run.seconds_total}}}};
}

SimulateLidarRun runSimulateLidar(const fs::path& out, const SimulateLidarParams& P) {
  validateParams(P);
  io::OutputTransaction outputs(out);  // locked and writable before the work
  const auto t_start = std::chrono::steady_clock::now();
  SimulateLidarRun run;
  run.drive_dir = io::kittiDriveDir(out, P.date, P.drive);
  run.frames = P.lidar.frames;

  io::writeKittiCalibration(out / P.date);  // the simulator uses what a reader will parse:
  const io::KittiCalibration calib = io::writtenKittiCalibration();
  const sim::LidarDrive drive(P.lidar, calib, static_cast<uint64_t>(P.seed));
  const sim::LidarScene& scene = drive.scene();
  if (drive.endArcLength() > scene.road().length() - 10.0)
    throw ConfigError(
        std::string(SimulateLidarParams::kName) + "::frames = " + std::to_string(P.lidar.frames) +
        ". Violated constraint: the drive (ends at " + std::to_string(drive.endArcLength()) +
        " m) must stay 10 m inside the generated road (" + std::to_string(scene.road().length()) +
        " m); use fewer frames, a lower ego_speed or longer straights");
  run.road_length = scene.road().length();
  run.primitives = scene.statics().size();
  run.moving_vehicles = scene.movers().size();
  MAPFUSE_INFO("simulate-lidar: road " << run.road_length << " m, " << run.primitives
                                       << " primitives, " << run.moving_vehicles
                                       << " moving cars -> " << run.drive_dir.string());

  io::MercatorAnchor anchor{P.lat0, P.lon0, P.alt0, drive.imuPose(0.0).translation()};
  const double dt = 1.0 / P.lidar.frame_rate;
  std::vector<std::string> ts, ts_start, ts_end, poses;
  Progress progress("frames", static_cast<std::size_t>(P.lidar.frames));
  for (int k = 0; k < P.lidar.frames; ++k) {
    const sim::LidarFrame f = drive.frame(k);
    run.seconds_lidar += f.seconds_lidar;
    run.seconds_camera += f.seconds_camera;
    const auto t0 = std::chrono::steady_clock::now();
    writeFrame(run.drive_dir, k, f, dt, anchor);
    run.seconds_write += seconds(t0);
    const double abs_t = P.start_time + f.time;
    ts.push_back(io::formatKittiTimestamp(P.date, abs_t));
    ts_start.push_back(io::formatKittiTimestamp(P.date, abs_t - 0.5 * dt));
    ts_end.push_back(io::formatKittiTimestamp(P.date, abs_t + 0.5 * dt));
    poses.push_back(poseLine(f.T_world_velo));
    run.points.add(f.scan);
    progress.advance();
  }
  progress.finish();

  const fs::path& dir = run.drive_dir;
  io::writeLines(dir / "image_02" / "timestamps.txt", ts);
  io::writeLines(dir / "velodyne_points" / "timestamps.txt", ts);
  io::writeLines(dir / "velodyne_points" / "timestamps_start.txt", ts_start);
  io::writeLines(dir / "velodyne_points" / "timestamps_end.txt", ts_end);
  io::writeLines(dir / "oxts" / "timestamps.txt", ts);
  io::writeOxtsDataformat(dir / "oxts" / "dataformat.txt");
  io::writeLines(dir / "ground_truth" / "poses_world_velo.txt", poses);
  run.seconds_total = seconds(t_start);
  io::writeResolvedConfig(dir, kStage, paramsToJson(P));
  io::writeSummary(dir, kStage, toJson(run));
  outputs.commit();
  return run;
}

}  // namespace mapfuse::stages
