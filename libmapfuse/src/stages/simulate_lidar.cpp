#include "mapfuse/stages/simulate_lidar.hpp"

#include <chrono>
#include <cstdio>

#include "mapfuse/core/log.hpp"
#include "mapfuse/core/progress.hpp"
#include "mapfuse/io/kitti_calib.hpp"
#include "mapfuse/io/kitti_raw_writer.hpp"
#include "mapfuse/io/semantic_image.hpp"
#include "mapfuse/io/semantic_kitti.hpp"
#include "mapfuse/io/stage_report.hpp"
#include "mapfuse/io/velodyne.hpp"
#include "mapfuse/sim/lidar_camera.hpp"
#include "mapfuse/sim/lidar_drive.hpp"

namespace mapfuse::stages {
namespace {
constexpr const char* kStage = "simulate-lidar";
constexpr const char* kStageName = "SimulateLidarParams";

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
}  // namespace

void SimulateLidarParams::validate() const {
  const auto positive = [](double x) { return x > 0.0; };
  const auto share = [](double x) { return x >= 0.0 && x <= 1.0; };
  requireParam(date.size() == 10 && date[4] == '_' && date[7] == '_', kStageName, "date", date,
               "YYYY_MM_DD");
  requireParam(!drive.empty() && drive.find('/') == std::string::npos, kStageName, "drive", drive,
               "non-empty, no '/'");
  requireParam(frames >= 1, kStageName, "frames", frames, ">= 1");
  requireParam(positive(frame_rate), kStageName, "frame_rate", frame_rate, "> 0");
  requireParam(ego_speed >= 0.0, kStageName, "ego_speed", ego_speed, ">= 0");
  requireParam(ego_start >= 0.0, kStageName, "ego_start", ego_start, ">= 0");
  requireParam(positive(velo_height), kStageName, "velo_height", velo_height, "> 0");
  requireParam(positive(road_half_width), kStageName, "road_half_width", road_half_width, "> 0");
  requireParam(positive(sidewalk_width), kStageName, "sidewalk_width", sidewalk_width, "> 0");
  requireParam(curb_height >= 0.0 && curb_height < velo_height, kStageName, "curb_height",
               curb_height, "in [0, velo_height)");
  requireParam(positive(lane_width) && lane_width <= road_half_width, kStageName, "lane_width",
               lane_width, "in (0, road_half_width]");
  requireParam(positive(straight_min) && straight_min <= straight_max, kStageName, "straight_min",
               straight_min, "in (0, straight_max]");
  requireParam(positive(turn_radius_min) && turn_radius_min <= turn_radius_max, kStageName,
               "turn_radius_min", turn_radius_min, "in (0, turn_radius_max]");
  requireParam(turn_radius_min > road_half_width + sidewalk_width, kStageName, "turn_radius_min",
               turn_radius_min, "> road_half_width + sidewalk_width");
  requireParam(share(building_share), kStageName, "building_share", building_share, "in [0, 1]");
  requireParam(share(fence_share) && building_share + fence_share <= 1.0, kStageName, "fence_share",
               fence_share, "in [0, 1 - building_share]");
  requireParam(positive(building_height_min) && building_height_min <= building_height_max,
               kStageName, "building_height_min", building_height_min,
               "in (0, building_height_max]");
  requireParam(positive(pole_spacing), kStageName, "pole_spacing", pole_spacing, "> 0");
  requireParam(positive(tree_spacing), kStageName, "tree_spacing", tree_spacing, "> 0");
  requireParam(share(parked_share), kStageName, "parked_share", parked_share, "in [0, 1]");
  requireParam(moving_vehicles >= 0 && moving_vehicles < 60000, kStageName, "moving_vehicles",
               moving_vehicles, "in [0, 60000)");
  requireParam(azimuth_steps >= 8, kStageName, "azimuth_steps", azimuth_steps, ">= 8");
  requireParam(lidar_min_range >= 0.0 && lidar_min_range < lidar_max_range, kStageName,
               "lidar_min_range", lidar_min_range, "in [0, lidar_max_range)");
  requireParam(range_noise >= 0.0, kStageName, "range_noise", range_noise, ">= 0");
  requireParam(share(dropout) && dropout < 1.0, kStageName, "dropout", dropout, "in [0, 1)");
  requireParam(positive(camera_max_range), kStageName, "camera_max_range", camera_max_range, "> 0");
  for (const auto& [name, value] : {std::pair{"sidewalk_as_road", sidewalk_as_road},
                                    {"road_as_sidewalk", road_as_sidewalk},
                                    {"fence_as_building", fence_as_building},
                                    {"building_as_fence", building_as_fence}})
    requireParam(share(value), kStageName, name, value, "in [0, 1]");
  requireParam(positive(confusion_scale), kStageName, "confusion_scale", confusion_scale, "> 0");
  requireParam(blobs_per_frame >= 0.0, kStageName, "blobs_per_frame", blobs_per_frame, ">= 0");
  requireParam(positive(blob_radius_min) && blob_radius_min <= blob_radius_max, kStageName,
               "blob_radius_min", blob_radius_min, "in (0, blob_radius_max]");
  requireParam(bleed_sigma >= 0.0, kStageName, "bleed_sigma", bleed_sigma, ">= 0");
  requireParam(confidence > 0.0 && confidence <= 1.0, kStageName, "confidence", confidence,
               "in (0, 1]");
  requireParam(std::abs(lat0) < 85.0, kStageName, "lat0", lat0, "|lat0| < 85");
  requireParam(std::abs(lon0) <= 180.0, kStageName, "lon0", lon0, "|lon0| <= 180");
  requireParam(start_time >= 0.0 && start_time + frames / frame_rate < 86400.0, kStageName,
               "start_time", start_time, "the drive must end before midnight");
}

sim::StreetParams SimulateLidarParams::street() const {
  sim::StreetParams s;
  s.seed = static_cast<uint64_t>(seed);
  s.profile.road_half_width = road_half_width;
  s.profile.sidewalk_width = sidewalk_width;
  s.profile.curb_height = curb_height;
  s.profile.lane_width = lane_width;
  s.straight_min = straight_min;
  s.straight_max = straight_max;
  s.turn_radius_min = turn_radius_min;
  s.turn_radius_max = turn_radius_max;
  s.building_share = building_share;
  s.fence_share = fence_share;
  s.building_height_min = building_height_min;
  s.building_height_max = building_height_max;
  s.pole_spacing = pole_spacing;
  s.tree_spacing = tree_spacing;
  s.parked_share = parked_share;
  s.moving_vehicles = moving_vehicles;
  s.ego_start = ego_start;
  s.ego_speed = ego_speed;
  return s;
}

sim::LidarSensorParams SimulateLidarParams::sensor() const {
  sim::LidarSensorParams s;
  s.azimuth_steps = azimuth_steps;
  s.min_range = lidar_min_range;
  s.max_range = lidar_max_range;
  s.range_noise = range_noise;
  s.dropout = dropout;
  return s;
}

sim::NetworkErrorParams SimulateLidarParams::network() const {
  sim::NetworkErrorParams n;
  n.offset_u = offset_u;
  n.offset_v = offset_v;
  n.sidewalk_as_road = sidewalk_as_road;
  n.road_as_sidewalk = road_as_sidewalk;
  n.fence_as_building = fence_as_building;
  n.building_as_fence = building_as_fence;
  n.confusion_scale = confusion_scale;
  n.blobs_per_frame = blobs_per_frame;
  n.blob_radius_min = blob_radius_min;
  n.blob_radius_max = blob_radius_max;
  n.bleed_sigma = bleed_sigma;
  n.confidence = confidence;
  return n;
}

nlohmann::json runSimulateLidar(const std::filesystem::path& out, const SimulateLidarParams& P) {
  P.validate();
  const auto t_start = std::chrono::steady_clock::now();
  const std::filesystem::path date_dir = out / P.date;
  const std::filesystem::path drive_dir = io::kittiDriveDir(out, P.date, P.drive);

  // Calibration first: the simulator uses exactly what a reader will parse.
  io::writeKittiCalibration(date_dir);
  const io::KittiCalibration calib = io::readKittiCalibration(date_dir);
  const Pose3 T_imu_velo = calib.T_velo_imu.inverse();

  const sim::LidarScene scene = sim::generateStreet(P.street());
  const sim::EgoDrive ego{P.ego_start, P.ego_speed, -0.5 * P.lane_width, P.velo_height};
  const double s_end = P.ego_start + P.ego_speed * (P.frames - 1) / P.frame_rate;
  if (s_end > scene.road().length() - 10.0)
    throw ConfigError(std::string(kStageName) + "::frames = " + std::to_string(P.frames) +
                      ". Violated constraint: the drive (ends at " + std::to_string(s_end) +
                      " m) must stay 10 m inside the generated road (" +
                      std::to_string(scene.road().length()) +
                      " m); use fewer frames, a lower "
                      "ego_speed or longer straights");
  MAPFUSE_INFO("simulate-lidar: road " << scene.road().length() << " m, " << scene.statics().size()
                                       << " primitives, " << scene.movers().size()
                                       << " moving cars -> " << drive_dir.string());

  io::MercatorAnchor anchor;
  anchor.lat0 = P.lat0;
  anchor.lon0 = P.lon0;
  anchor.alt0 = P.alt0;
  anchor.world_origin = sim::egoImuPose(scene.road(), ego, T_imu_velo, 0.0).translation();

  const sim::LidarSensorParams sensor = P.sensor();
  const sim::NetworkErrorParams network = P.network();
  std::vector<std::string> ts, ts_start, ts_end, poses;
  std::size_t points_total = 0, points_min = SIZE_MAX, points_max = 0, moving_points = 0;
  std::vector<std::size_t> class_points(kNumLidarClasses, 0);
  double t_lidar = 0.0, t_camera = 0.0, t_write = 0.0;
  Progress progress("frames", static_cast<std::size_t>(P.frames));
  for (int k = 0; k < P.frames; ++k) {
    const double t = k / P.frame_rate, dt = 1.0 / P.frame_rate;
    const std::string name = io::kittiFrameName(k);
    const Pose3 T_world_imu = sim::egoImuPose(scene.road(), ego, T_imu_velo, t);
    const Pose3 T_world_velo = T_world_imu * T_imu_velo;
    const uint64_t seed = static_cast<uint64_t>(P.seed);

    auto t0 = std::chrono::steady_clock::now();
    const sim::LidarScan scan = sim::scanLidar(scene, T_world_velo, t, sensor,
                                               sim::hashKey(seed, static_cast<uint64_t>(k), 1));
    t_lidar += seconds(t0);
    t0 = std::chrono::steady_clock::now();
    const sim::CameraFrame cam =
        sim::renderLabels(scene, calib, T_world_velo, t, P.camera_max_range);
    const io::SemanticImage probs =
        sim::networkProbabilities(cam, network, sim::hashKey(seed, static_cast<uint64_t>(k), 2));
    t_camera += seconds(t0);

    t0 = std::chrono::steady_clock::now();
    io::VelodyneScan vs;
    vs.points.reserve(scan.points.size());
    vs.reflectance.reserve(scan.points.size());
    for (const auto& p : scan.points) {
      vs.points.emplace_back(p.head<3>());
      vs.reflectance.push_back(p.w());
    }
    io::writeVelodyneBin(drive_dir / "velodyne_points" / "data" / (name + ".bin"), vs);
    io::writeSemanticKittiLabels(drive_dir / "labels" / (name + ".label"), scan.labels);
    io::writePngBgr(drive_dir / "image_02" / "data" / (name + ".png"), cam.width, cam.height,
                    sim::shadeLabels(cam));
    io::writeSemanticImage(io::semanticsDir(drive_dir) / (name + ".prob"), probs);
    io::writeSemanticImage(drive_dir / "ground_truth" / "label_02" / (name + ".png"),
                           io::SemanticImage::fromLabels(cam.width, cam.height, cam.labels));
    // OXTS with velocities and yaw rate from the neighbouring poses.
    geo::OxtsRecord rec = io::oxtsFromPose(T_world_imu, anchor);
    const Pose3 T_next = sim::egoImuPose(scene.road(), ego, T_imu_velo, t + dt);
    const Eigen::Vector3d v_world = (T_next.translation() - T_world_imu.translation()) / dt;
    const Eigen::Vector3d v_body = T_world_imu.linear().transpose() * v_world;
    rec.ve = v_world.x();
    rec.vn = v_world.y();
    rec.vu = v_world.z();
    rec.vf = v_body.x();
    rec.vl = v_body.y();
    rec.az = rec.au = 9.81;
    rec.wz = rec.wu = logSE3(T_world_imu.inverse() * T_next)(5) / dt;
    io::writeLines(drive_dir / "oxts" / "data" / (name + ".txt"), {io::formatOxtsLine(rec)});
    t_write += seconds(t0);

    const double abs_t = P.start_time + t;
    ts.push_back(io::formatKittiTimestamp(P.date, abs_t));
    ts_start.push_back(io::formatKittiTimestamp(P.date, abs_t - 0.5 * dt));
    ts_end.push_back(io::formatKittiTimestamp(P.date, abs_t + 0.5 * dt));
    poses.push_back(poseLine(T_world_velo));
    points_total += scan.points.size();
    points_min = std::min(points_min, scan.points.size());
    points_max = std::max(points_max, scan.points.size());
    for (uint32_t w : scan.labels) {
      const uint16_t id = static_cast<uint16_t>(w & 0xFFFF);
      ++class_points[static_cast<int>(lidarClassFromSemanticKitti(id))];
      moving_points += id == sim::kSemanticKittiMovingCar;
    }
    progress.advance();
  }
  progress.finish();

  io::writeLines(drive_dir / "image_02" / "timestamps.txt", ts);
  io::writeLines(drive_dir / "velodyne_points" / "timestamps.txt", ts);
  io::writeLines(drive_dir / "velodyne_points" / "timestamps_start.txt", ts_start);
  io::writeLines(drive_dir / "velodyne_points" / "timestamps_end.txt", ts_end);
  io::writeLines(drive_dir / "oxts" / "timestamps.txt", ts);
  io::writeOxtsDataformat(drive_dir / "oxts" / "dataformat.txt");
  io::writeLines(drive_dir / "ground_truth" / "poses_world_velo.txt", poses);

  nlohmann::json classes = nlohmann::json::object();
  for (int c = 0; c < kNumLidarClasses; ++c)
    classes[lidarClassName(static_cast<LidarClass>(c))] = class_points[c];
  nlohmann::json summary = {{"drive_dir", drive_dir.string()},
                            {"frames", P.frames},
                            {"road_length_m", scene.road().length()},
                            {"primitives", scene.statics().size()},
                            {"moving_vehicles", scene.movers().size()},
                            {"points_per_scan",
                             {{"mean", static_cast<double>(points_total) / P.frames},
                              {"min", points_min},
                              {"max", points_max}}},
                            {"points_per_class", classes},
                            {"moving_vehicle_points", moving_points},
                            {"timings_s",
                             {{"lidar", t_lidar},
                              {"camera_and_network", t_camera},
                              {"write", t_write},
                              {"total", seconds(t_start)}}}};
  io::writeResolvedConfig(drive_dir, kStage, paramsToJson(P));
  io::writeSummary(drive_dir, kStage, summary);
  return summary;
}

}  // namespace mapfuse::stages
