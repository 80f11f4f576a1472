#include "mapfuse/stages/simulate_lidar.hpp"

#include <chrono>

#include "mapfuse/cli/params.hpp"
#include "mapfuse/core/error.hpp"
#include "mapfuse/core/log.hpp"
#include "mapfuse/core/progress.hpp"
#include "mapfuse/io/kitti_calib.hpp"
#include "mapfuse/io/kitti_raw_writer.hpp"
#include "mapfuse/io/output_transaction.hpp"
#include "mapfuse/io/stage_report.hpp"
#include "mapfuse/sim/lidar_drive_writer.hpp"

namespace mapfuse::stages {
namespace {
namespace fs = std::filesystem;
constexpr const char* kSimulateLidar = "simulate-lidar";

double seconds(std::chrono::steady_clock::time_point a) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count();
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

  const io::MercatorAnchor anchor{P.lat0, P.lon0, P.alt0, drive.imuPose(0.0).translation()};
  sim::LidarDriveWriter writer(run.drive_dir, P.date, P.start_time, 1.0 / P.lidar.frame_rate,
                               anchor);
  Progress progress("frames", static_cast<std::size_t>(P.lidar.frames));
  for (int k = 0; k < P.lidar.frames; ++k) {
    const sim::LidarFrame f = drive.frame(k);
    run.seconds_lidar += f.seconds_lidar;
    run.seconds_camera += f.seconds_camera;
    const auto t0 = std::chrono::steady_clock::now();
    writer.add(k, f);
    run.seconds_write += seconds(t0);
    run.points.add(f.scan);
    progress.advance();
  }
  progress.finish();
  writer.finish();
  run.seconds_total = seconds(t_start);
  io::writeResolvedConfig(run.drive_dir, kSimulateLidar, paramsToJson(P));
  io::writeSummary(run.drive_dir, kSimulateLidar, toJson(run));
  outputs.commit();
  return run;
}

}  // namespace mapfuse::stages
