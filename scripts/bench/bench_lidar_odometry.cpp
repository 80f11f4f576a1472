// Benchmark of the LiDAR odometry (issue 24; docs/performance-lidar.md), on one core:
//  kitti  real KITTI raw drive without truth: displacement of chosen frames from the first at
//         strides 1, 2 and 3, against the independent static-structure registration
//         (lidar/static_registration.hpp); rotations' orthonormality; scans per second.
//  sim    simulate-lidar scenes (moving cars, no OXTS: the truth only scores) generated in
//         process without the camera: KITTI odometry metric (translation %, rotation deg/m over
//         segments of 100..800 m, or the longest the drive allows).
// Prints Markdown on stdout; scripts/bench/bench_lidar_odometry.sh writes the document.
#include <omp.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <opencv2/core.hpp>

#include "mapfuse/core/log.hpp"
#include "mapfuse/io/kitti_calib.hpp"
#include "mapfuse/io/kitti_raw.hpp"
#include "mapfuse/io/kitti_raw_writer.hpp"
#include "mapfuse/io/png_frames.hpp"
#include "mapfuse/io/velodyne.hpp"
#include "mapfuse/lidar/drive_odometry.hpp"
#include "mapfuse/lidar/static_registration.hpp"
#include "mapfuse/sim/lidar_drive.hpp"
#include "mapfuse/sim/lidar_scene_generator.hpp"
#include "mapfuse/sim/lidar_sensor.hpp"
#include "mapfuse/stages/simulate_lidar.hpp"

using namespace mapfuse;
using Clock = std::chrono::steady_clock;

namespace {
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}
constexpr double kDeg = 180.0 / M_PI;

struct Variant {
  std::string name;
  lidar::OdometrySettings s;
};

/// Odometry over scans with times; returns the poses and the wall time of add() alone.
struct Run {
  std::vector<Pose3> poses;
  std::vector<lidar::OdometryStep> steps;
  double seconds = 0;
};
Run runOdometry(const std::vector<std::vector<Eigen::Vector3f>>& scans,
                const std::vector<double>& times, const lidar::OdometrySettings& s, bool verbose,
                const std::vector<int>& names,
                const std::vector<std::vector<uint8_t>>* masks = nullptr) {
  lidar::ScanOdometry odo(s);
  Run r;
  for (std::size_t i = 0; i < scans.size(); ++i) {
    const auto t = Clock::now();
    const auto& st =
        odo.add(scans[i], i == 0 ? 0.0 : times[i] - times[i - 1], masks ? &(*masks)[i] : nullptr);
    r.seconds += since(t);
    if (verbose && !st.first) {
      const auto& a = st.assessment;
      std::fprintf(stderr,
                   "frame %3d it %3d inl %.3f rmse %.3f thr %.2f pts %5zu ru %5zu v %.2f "
                   "dev %.3f c %.3f %s %s\n",
                   names[i], st.iterations, st.inlier_share, st.rmse, st.threshold, st.points,
                   st.road_user_points, a.speed, a.deviation_m, a.constraint,
                   st.trusted() ? "ok" : "UNTRUSTED", a.reasons.c_str());
    }
  }
  r.poses = odo.poses();
  r.steps = odo.steps();
  return r;
}

double maxOrthoError(const std::vector<Pose3>& poses) {
  double e = 0;
  for (const auto& T : poses)
    e = std::max(
        e,
        (T.linear().transpose() * T.linear() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff());
  return e;
}

// ---- KITTI odometry metric (devkit evaluate_odometry.cpp) ----
struct Drift {
  double t_pct = 0, r_deg_per_m = 0;
  int segments = 0;
  std::string lengths;
};
Drift kittiDrift(const std::vector<Pose3>& gt, const std::vector<Pose3>& est) {
  std::vector<double> dist(gt.size(), 0.0);
  for (std::size_t i = 1; i < gt.size(); ++i)
    dist[i] = dist[i - 1] + (gt[i].translation() - gt[i - 1].translation()).norm();
  std::vector<double> lengths;
  for (double L = 100; L <= 800; L += 100)
    if (L <= dist.back()) lengths.push_back(L);
  if (lengths.empty()) lengths.push_back(std::floor(dist.back() / 10.0) * 10.0);  // longest
  Drift d;
  for (double L : lengths) d.lengths += (d.lengths.empty() ? "" : ", ") + std::to_string(int(L));
  for (std::size_t first = 0; first < gt.size(); first += 10)
    for (double L : lengths) {
      std::size_t last = first;
      while (last < gt.size() && dist[last] < dist[first] + L) ++last;
      if (last >= gt.size()) continue;
      const Pose3 dg = gt[first].inverse() * gt[last], de = est[first].inverse() * est[last];
      const Pose3 e = de.inverse() * dg;
      const double angle = std::acos(std::clamp((e.linear().trace() - 1.0) / 2.0, -1.0, 1.0));
      d.t_pct += 100.0 * e.translation().norm() / L;
      d.r_deg_per_m += angle * kDeg / L;
      ++d.segments;
    }
  if (d.segments) {
    d.t_pct /= d.segments;
    d.r_deg_per_m /= d.segments;
  }
  return d;
}

lidar::OdometrySettings g_base;  // the defaults, or what --set changed

/// The default and the measured alternatives (docs/performance-lidar.md, odometry).
std::vector<Variant> variants(const std::string& which) {
  std::vector<Variant> out;
  const lidar::OdometrySettings base = g_base;
  out.push_back({"default", base});
  if (which == "default") return out;
  lidar::OdometrySettings v = base;
  v.deskew = false;
  out.push_back({"no de-skew", v});
  v = base;
  v.exclude_road_users = true;
  out.push_back({"road users left out (geometric rule)", v});
  v = base;
  v.keyframe_distance = 0;
  v.keyframe_angle = 0;
  out.push_back({"every sweep enters the map (no keyframes)", v});
  v = base;
  v.source_spacing = 0.5;
  out.push_back({"registered at 0.5 m instead of 1.0 m", v});
  v = base;
  v.registration.point_to_plane = false;
  out.push_back({"point-to-point", v});
  v = base;
  v.registration.point_to_plane = false;
  v.keyframe_distance = 0;
  v.keyframe_angle = 0;
  v.deskew = false;
  out.push_back({"kiss-icp-like: point-to-point, every sweep, no de-skew", v});
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("LiDAR odometry benchmark (one core)", "bench_lidar_odometry");
  app.require_subcommand(1);
  std::string drive_dir, which = "all";
  std::vector<int> check_frames{30, 77};
  int first = 0, last = 77, ref_gap = 5;
  bool verbose = false;
  std::vector<int> seeds{1, 2, 3};
  int sim_frames = 300;
  auto* kitti = app.add_subcommand("kitti", "real KITTI raw drive without truth");
  kitti->add_option("--drive", drive_dir, "KITTI raw drive folder")->required();
  kitti->add_option("--first", first, "first frame")->capture_default_str();
  kitti->add_option("--last", last, "last frame")->capture_default_str();
  kitti->add_option("--check", check_frames, "frames whose displacement is compared");
  double ref_min_height = 0.0;
  kitti
      ->add_option("--ref-min-height", ref_min_height, "static points lower than this are left out")
      ->capture_default_str();
  kitti->add_option("--ref-gap", ref_gap, "frame gap of the static reference chain")
      ->capture_default_str();
  auto* sim = app.add_subcommand("sim", "simulate-lidar scenes, scored by the KITTI metric");
  sim->add_option("--seeds", seeds, "scene seeds");
  sim->add_option("--frames", sim_frames, "frames per drive")->capture_default_str();
  double ego_speed = 8.0;
  sim->add_option("--ego-speed", ego_speed, "m/s")->capture_default_str();
  app.add_option("--variants", which, "default | all")->capture_default_str();
  app.add_flag("--verbose", verbose, "per-step lines on stderr");
  app.add_option("--keyframe-distance", g_base.keyframe_distance, "m")->capture_default_str();
  app.add_option("--fine-threshold", g_base.fine_threshold, "m")->capture_default_str();
  app.add_option("--source-spacing", g_base.source_spacing, "m")->capture_default_str();
  app.add_option("--scan-spacing", g_base.scan_spacing, "m")->capture_default_str();
  app.add_option("--deskew", g_base.deskew, "de-skew each sweep")->capture_default_str();
  app.add_option("--max-points-per-voxel", g_base.max_points_per_voxel, "local map")
      ->capture_default_str();
  int reps = 3;
  auto* speed = app.add_subcommand("speed", "scans per second of the default odometry, one core");
  speed->add_option("--drive", drive_dir, "KITTI raw drive folder")->required();
  speed->add_option("--first", first, "first frame")->capture_default_str();
  speed->add_option("--last", last, "last frame")->capture_default_str();
  speed->add_option("--reps", reps, "repetitions (the median is reported)")->capture_default_str();
  std::string picture_out;
  int picture_frame = 0;
  auto* picture = app.add_subcommand("picture", "top-down picture of one scan's geometric split");
  picture->add_option("--drive", drive_dir, "KITTI raw drive folder")->required();
  picture->add_option("--frame", picture_frame, "frame")->capture_default_str();
  picture->add_option("-o", picture_out, "PNG")->required();
  CLI11_PARSE(app, argc, argv);
  if (speed->parsed()) {
    // Sweeps preloaded; ScanOdometry::add timed alone (what the stage runs per frame after
    // reading the file), one core.
    const auto drive = io::openKittiRawDrive(drive_dir, {first, last, 1});
    std::vector<std::vector<Eigen::Vector3f>> scans;
    for (const auto& f : drive.frames) scans.push_back(io::readVelodyneBin(f.velodyne).points);
    std::vector<double> rates;
    for (int r = 0; r < reps; ++r) {
      lidar::ScanOdometry odo(g_base);
      const auto t = Clock::now();
      for (std::size_t i = 0; i < scans.size(); ++i) odo.add(scans[i], 0.1);
      rates.push_back(double(scans.size()) / since(t));
    }
    std::sort(rates.begin(), rates.end());
    std::printf("%zu sweeps, %.1f scans/s (median of %d; min %.1f, max %.1f)\n", scans.size(),
                rates[rates.size() / 2], reps, rates.front(), rates.back());
    return 0;
  }
  if (picture->parsed()) {
    const auto drive = io::openKittiRawDrive(drive_dir, {picture_frame, picture_frame, 1});
    const auto scan = io::readVelodyneBin(drive.frames[0].velodyne).points;
    std::vector<Eigen::Vector3d> pts;
    for (const auto& p : scan)
      if (p.norm() > 3 && p.norm() < 60) pts.push_back(p.cast<double>());
    lidar::SceneGeometryStats st;
    const auto kinds = lidar::splitScanGeometry(pts, lidar::SceneGeometrySettings{}, &st);
    const int W = 1200;  // 0.1 m/px, 60 m each side
    cv::Mat img(W, W, CV_8UC3, cv::Scalar(255, 255, 255));
    const cv::Vec3b colour[3] = {{200, 200, 200}, {40, 40, 40}, {0, 0, 230}};
    for (int pass = 0; pass < 3; ++pass)  // ground first, road users on top
      for (std::size_t i = 0; i < pts.size(); ++i) {
        if (int(kinds[i]) != pass) continue;
        const int u = int(W / 2 - pts[i].y() * 10), v = int(W / 2 - pts[i].x() * 10);
        if (u >= 0 && u < W && v >= 0 && v < W) img.at<cv::Vec3b>(v, u) = colour[pass];
      }
    // Side view below: x to the right, z up, points with |y| < 8 m, 0.05 m/px.
    cv::Mat side(300, W, CV_8UC3, cv::Scalar(255, 255, 255));
    for (int pass = 0; pass < 3; ++pass)
      for (std::size_t i = 0; i < pts.size(); ++i) {
        if (int(kinds[i]) != pass || std::abs(pts[i].y()) > 8) continue;
        const int u = int(W / 2 + pts[i].x() * 20), v = int(300 - (pts[i].z() + 3.0) * 30);
        if (u >= 0 && u < W && v >= 0 && v < 300) side.at<cv::Vec3b>(v, u) = colour[pass];
      }
    cv::Mat both;
    cv::vconcat(img, side, both);
    io::writePngFrame(picture_out, both);
    std::printf("ground %zu static %zu road users %zu (%zu of %zu segments)\n", st.ground,
                st.static_points, st.road_user, st.road_user_segments, st.segments);
    return 0;
  }
  setLogLevel(LogLevel::kWarn);
  omp_set_num_threads(1);

  if (kitti->parsed()) {
    const auto drive = io::openKittiRawDrive(drive_dir, {first, last, 1});
    std::map<int, std::vector<Eigen::Vector3f>> scans;
    for (const auto& f : drive.frames) scans[f.index] = io::readVelodyneBin(f.velodyne).points;
    // Independent reference: static structure, chained pairwise GICP every ref_gap frames.
    std::map<int, Pose3> ref{{first, Pose3::Identity()}};
    {
      Pose3 T = Pose3::Identity(), step = Pose3::Identity();
      int a = first;
      std::vector<int> chain;
      for (int k = first + ref_gap; k <= last; k += ref_gap) chain.push_back(k);
      for (int c : check_frames)
        if ((c - first) % ref_gap) chain.push_back(c);
      std::sort(chain.begin(), chain.end());
      for (int b : chain) {
        double fit = 0;
        // Constant-velocity start: the previous pair's motion, scaled to this pair's gap.
        const Pose3 init = lidar::scaleMotion(step, double(b - a) / ref_gap);
        lidar::StaticRegistrationSettings rs;
        rs.min_height = ref_min_height;
        const Pose3 pair = lidar::registerStaticStructure(scans.at(a), scans.at(b), init, rs, &fit);
        if ((b - first) % ref_gap == 0) step = pair;
        if ((b - first) % ref_gap == 0) {
          T = T * pair;
          ref[b] = T;
          a = b;
        } else {
          ref[b] = T * pair;
        }
        if (verbose)
          std::fprintf(stderr, "ref %d: %.3f m (fitness %.2f)\n", b, ref[b].translation().norm(),
                       fit);
      }
    }
    std::printf("| variant | stride | ");
    for (int c : check_frames) std::printf("%d->%d (m) | ", first, c);
    std::printf("vs static ref | max stride spread | untrusted | scans/s | max abs(R^T R - I) |\n");
    std::printf("|---|---|");
    for (std::size_t i = 0; i < check_frames.size(); ++i) std::printf("---|");
    std::printf("---|---|---|---|---|\n");
    const auto vs = variants(which);
    for (const auto& v : vs) {
      std::map<int, std::vector<double>> disp;
      for (int stride = 1; stride <= 3; ++stride) {
        std::vector<int> frames;
        for (int k = first; k <= last; k += stride) frames.push_back(k);
        if (frames.back() != last) frames.push_back(last);
        std::vector<std::vector<Eigen::Vector3f>> sc;
        std::vector<double> times;
        for (int k : frames) {
          sc.push_back(scans.at(k));
          times.push_back(0.1 * (k - first));
        }
        const Run r =
            runOdometry(sc, times, v.s, verbose && stride == 1 && &v == &vs.front(), frames);
        int untrusted = 0;
        for (const auto& st : r.steps) untrusted += !st.trusted();
        std::printf("| %s | %d | ", v.name.c_str(), stride);
        std::string vs;
        for (int c : check_frames) {
          double d = NAN;
          for (std::size_t i = 0; i < frames.size(); ++i)
            if (frames[i] == c) d = r.poses[i].translation().norm();
          if (std::isnan(d)) {  // not on this stride
            std::printf("- | ");
            continue;
          }
          disp[c].push_back(d);
          std::printf("%.3f | ", d);
          char b[64];
          std::snprintf(b, sizeof b, "%s%+.1f %%", vs.empty() ? "" : ", ",
                        100.0 * (d / ref.at(c).translation().norm() - 1.0));
          vs += b;
        }
        std::string spread = "-";
        if (stride == 3) {
          double worst = 0;
          for (auto& [c, ds] : disp) {
            const auto [lo, hi] = std::minmax_element(ds.begin(), ds.end());
            worst = std::max(worst, (*hi - *lo) / *lo);
          }
          char b[32];
          std::snprintf(b, sizeof b, "%.1f %%", 100 * worst);
          spread = b;
        }
        std::printf("%s | %s | %d | %.1f | %.1e |\n", vs.c_str(), spread.c_str(), untrusted,
                    double(frames.size()) / r.seconds, maxOrthoError(r.poses));
      }
    }
    std::printf("\nStatic-structure reference (pairwise GICP every %d frames): ", ref_gap);
    for (int c : check_frames)
      std::printf("%d->%d %.3f m  ", first, c, ref.at(c).translation().norm());
    std::printf("\n");
    return 0;
  }

  // sim: scenes of simulate-lidar (its parameters and generator), scans cast in process.
  std::printf(
      "| variant | seed | frames | length (m) | segments (m) | translation (%%) | "
      "rotation (deg/m) | untrusted | scans/s |\n|---|---|---|---|---|---|---|---|---|\n");
  for (int64_t seed : seeds) {
    stages::SimulateLidarParams P;
    P.seed = seed;
    P.lidar.frames = sim_frames;
    P.lidar.street.straight_min = 110;
    P.lidar.street.straight_max = 160;
    P.lidar.street.ego_speed = ego_speed;
    const io::KittiCalibration calib = [&] {
      const auto dir = std::filesystem::temp_directory_path() / "bench_lidar_odometry_calib";
      io::writeKittiCalibration(dir);
      return io::readKittiCalibration(dir);
    }();
    const Pose3 T_imu_velo = calib.T_velo_imu.inverse();
    const sim::LidarDrive drive(P.lidar, calib, static_cast<uint64_t>(P.seed));
    const sim::LidarScene& scene = drive.scene();
    std::vector<std::vector<Eigen::Vector3f>> scans;
    std::vector<std::vector<uint8_t>> vehicle_masks;  // truth: cars, parked or moving
    std::vector<Pose3> gt;
    std::vector<double> times;
    omp_set_num_threads(omp_get_num_procs());  // casting only; the odometry runs on one core
    for (int k = 0; k < P.lidar.frames; ++k) {
      const double t = k / P.lidar.frame_rate;
      const Pose3 T = drive.imuPose(t) * T_imu_velo;
      const auto scan =
          sim::scanLidar(scene, T, t, P.lidar.sensor, sim::hashKey(uint64_t(seed), uint64_t(k), 1));
      std::vector<Eigen::Vector3f> pts;
      for (const auto& p : scan.points) pts.emplace_back(p.head<3>());
      scans.push_back(std::move(pts));
      std::vector<uint8_t> m;
      for (uint32_t w : scan.labels) m.push_back((w & 0xFFFF) == 10 || (w & 0xFFFF) == 252);
      vehicle_masks.push_back(std::move(m));
      gt.push_back(T);
      times.push_back(t);
    }
    omp_set_num_threads(1);
    std::vector<int> names(scans.size());
    for (std::size_t i = 0; i < names.size(); ++i) names[i] = int(i);
    double length = 0;
    for (std::size_t i = 1; i < gt.size(); ++i)
      length += (gt[i].translation() - gt[i - 1].translation()).norm();
    auto vs = variants(which);
    if (which != "default") {
      Variant t = vs.front();
      t.name = "vehicles left out by the simulator's truth";
      t.s.exclude_road_users = false;
      vs.push_back(t);
    }
    for (const auto& v : vs) {
      const bool truth = v.name.rfind("vehicles left out", 0) == 0;
      const Run r =
          runOdometry(scans, times, v.s, verbose, names, truth ? &vehicle_masks : nullptr);
      const Drift d = kittiDrift(gt, r.poses);
      int untrusted = 0;
      for (const auto& st : r.steps) untrusted += !st.trusted();
      double est = 0;
      for (std::size_t i = 1; i < r.poses.size(); ++i)
        est += (r.poses[i].translation() - r.poses[i - 1].translation()).norm();
      std::printf("| %s | %lld | %d | %.1f (odometry %.1f) | %s | %.2f | %.4f | %d | %.1f |\n",
                  v.name.c_str(), (long long)seed, P.lidar.frames, length, est, d.lengths.c_str(),
                  d.t_pct, d.r_deg_per_m, untrusted, double(scans.size()) / r.seconds);
    }
  }
  return 0;
}
