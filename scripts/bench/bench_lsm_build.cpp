// Benchmark of lsm-build (issue 6): frames per second per core of the geometric pipeline
// (vanishing-point calibration + ranging + triangulation + assembly, network excluded) on a
// simulated drive, and of the fallback perception (ENet road + BEV top-hat lanes) on KITTI.
// Prints a Markdown table on stdout; scripts/bench/bench_lsm_build.sh writes it to
// docs/performance-lsm-build.md.
#include <omp.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <iostream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "mapfuse/core/log.hpp"
#include "mapfuse/io/camera_calib.hpp"
#include "mapfuse/io/drive_frames.hpp"
#include "mapfuse/vehicle/dead_reckoning.hpp"
#include "mapfuse/vehicle/fallback_perception.hpp"
#include "mapfuse/vehicle/lsm_build.hpp"

using namespace mapfuse;
using Clock = std::chrono::steady_clock;

int main(int argc, char** argv) {
  CLI::App app("lsm-build benchmark", "bench_lsm_build");
  std::string drive, kitti, model, bev_png;
  int repeats = 5, kitti_frames = 3;
  app.add_option("--drive", drive, "simulated frames drive folder")->required();
  app.add_option("--kitti", kitti, "KITTI raw drive folder (fallback perception)");
  app.add_option("--model", model, "ENet model");
  app.add_option("--kitti-frames", kitti_frames, "KITTI frames to run the network on");
  app.add_option("--repeats", repeats, "repetitions of the geometric pipeline");
  app.add_option("--bev-png", bev_png, "write the BEV of KITTI frame 0 with detected lanes");
  CLI11_PARSE(app, argc, argv);
  setLogLevel(LogLevel::kWarn);

  // The drive as lsm-build reads it by default: observations, dead-reckoned ego-motion.
  const io::DriveFrames df = io::readDriveFrames(drive);
  vehicle::DriveData d;
  d.calib = df.calib;
  d.frames = df.observations;
  d.gps = df.gps;
  for (const auto& f : df.frames) d.stamps.push_back(f.stamp);
  d.T_odom_body = vehicle::deadReckon(df.imu, df.wheel, d.stamps, {});
  const vehicle::LsmBuildSettings settings;
  std::cout << "| measurement | frames | threads | seconds | frames/s | frames/s per core |\n"
            << "|---|---|---|---|---|---|\n";
  for (int threads : {1, omp_get_max_threads()}) {
    omp_set_num_threads(threads);
    double best = 1e300;
    for (int r = 0; r < repeats; ++r) {
      const auto t0 = Clock::now();
      const auto out = vehicle::buildLsm(d, settings);
      best = std::min(best, std::chrono::duration<double>(Clock::now() - t0).count());
      if (out.lsm.elements.empty()) return 1;
    }
    const double fps = double(d.frames.size()) / best;
    std::cout << "| calibration + ranging + triangulation + assembly (simulated, observations) | "
              << d.frames.size() << " | " << threads << " | " << best << " | " << fps << " | "
              << fps / threads << " |\n";
  }
  if (kitti.empty()) return 0;
  omp_set_num_threads(1);
  cv::setNumThreads(1);
  const auto calib = io::readKittiCameraCalib(std::filesystem::path(kitti).parent_path(), 1.65);
  vehicle::RoadSegmenter seg(model);
  double t_net = 0.0, t_lane = 0.0, t_aerial = 0.0, t_colour = 0.0;
  int aerial_boxes = 0, colour_boxes = 0;
  for (int i = 0; i < kitti_frames; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "%010d.png", i);
    const cv::Mat bgr =
        vehicle::readColorImage(std::filesystem::path(kitti) / "image_02/data" / name);
    const auto t0 = Clock::now();
    const vehicle::Segmentation sg = seg.segment(bgr);
    const cv::Mat road = sg.classes == vehicle::cityscapes::kRoad;
    const vehicle::PerceptionSettings ps;
    const auto t1 = Clock::now();
    const cv::Mat users = vehicle::roadUserMask(sg.classes, ps.road_user_margin);
    const auto det = vehicle::detectLanes(bgr, road, calib, vehicle::LaneDetectSettings{}, users);
    const auto t2 = Clock::now();
    aerial_boxes += int(vehicle::detectAerial(sg.classes, sg.confidence, ps.aerial).size());
    const auto t3 = Clock::now();
    colour_boxes +=
        int(vehicle::detectColourCues(bgr, calib.K, calib.ground.normal_cam.normalized(), ps.colour)
                .size());
    const auto t4 = Clock::now();
    t_colour += std::chrono::duration<double>(t4 - t3).count();
    t_net += std::chrono::duration<double>(t1 - t0).count();
    t_lane += std::chrono::duration<double>(t2 - t1).count();
    t_aerial += std::chrono::duration<double>(t3 - t2).count();
    if (i == 0 && !bev_png.empty()) {
      cv::Mat vis;
      cv::cvtColor(det.bev_gray, vis, cv::COLOR_GRAY2BGR);
      vis.setTo(cv::Scalar(0, 90, 0), det.bev_road == 0);
      const vehicle::LaneDetectSettings s;
      for (const auto& lane : det.lanes_ground)
        for (std::size_t k = 1; k < lane.size(); ++k) {
          auto px = [&](const Eigen::Vector2d& g) {
            return cv::Point(int((s.bev_half_width - g.y()) / s.bev_resolution),
                             int((s.bev_max_x - g.x()) / s.bev_resolution));
          };
          cv::line(vis, px(lane[k - 1]), px(lane[k]), cv::Scalar(0, 0, 255), 2);
        }
      cv::imwrite(bev_png, vis);
    }
  }
  std::cout << "| ENet segmentation + softmax probability (KITTI 1242x375, OpenCV DNN, 1 thread) | "
            << kitti_frames << " | 1 | " << t_net << " | " << kitti_frames / t_net << " | "
            << kitti_frames / t_net << " |\n"
            << "| road-user mask + BEV top-hat lane extraction + solid/dashed typing (excl. "
               "network) | "
            << kitti_frames << " | 1 | " << t_lane << " | " << kitti_frames / t_lane << " | "
            << kitti_frames / t_lane << " |\n"
            << "| sign/light/pole components (excl. network; " << aerial_boxes << " boxes) | "
            << kitti_frames << " | 1 | " << t_aerial << " | " << kitti_frames / t_aerial << " | "
            << kitti_frames / t_aerial << " |\n"
            << "| colour cues: red rings, lit lamps (" << colour_boxes << " boxes) | "
            << kitti_frames << " | 1 | " << t_colour << " | " << kitti_frames / t_colour << " | "
            << kitti_frames / t_colour << " |\n";
  return 0;
}
