// Benchmark of lidar-semantic-map (issue 7) on ONE core: (a) per-frame labelling (projection +
// clustering + forests + Bayesian fusion, lidar::fuseFrame, network and file reading excluded)
// on a simulate-lidar drive; (b) batch refinement (K-nearest mean-distance filter + vehicle-trace
// removal) of a synthetic >= 10M-voxel map; (c) bytes per voxel (map accounting and peak-RSS
// delta); optionally the ENet network on real KITTI frames. Prints a Markdown table on stdout;
// scripts/bench/bench_lidar.sh writes it to docs/performance-lidar.md.
#include <omp.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <opencv2/core.hpp>

#include "mapfuse/core/log.hpp"
#include "mapfuse/io/velodyne.hpp"
#include "mapfuse/lidar/classifier_training.hpp"
#include "mapfuse/lidar/drive_poses.hpp"
#include "mapfuse/lidar/refinement.hpp"
#include "mapfuse/lidar/scan_odometry.hpp"
#include "mapfuse/lidar/semantic_mapper.hpp"

using namespace mapfuse;
using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;

namespace {
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}
double peakRssBytes() {  // getrusage: ru_maxrss in KiB on Linux
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return 1024.0 * static_cast<double>(u.ru_maxrss);
}
double threadCpuSeconds() {  // CPU time of this thread: unaffected by other jobs' share
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}
double rssBytes() {  // current resident set, /proc/self/statm
  std::ifstream f("/proc/self/statm");
  double size = 0, resident = 0;
  f >> size >> resident;
  return resident * static_cast<double>(sysconf(_SC_PAGESIZE));
}
void row(const char* what, const char* target, const std::string& measured, const char* verdict) {
  std::printf("| %s | %s | %s | %s |\n", what, target, measured.c_str(), verdict);
}
std::string fmt(const char* f, double a, double b = 0, double c = 0, double d = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, f, a, b, c, d);
  return buf;
}

/// A synthetic street along x at 5 cm voxels, inserted with SemanticVoxelMap::insertVoxel until
/// the map holds `target` voxels. Per 5 cm slice: 30 m of ground (road z=0, sidewalks at the
/// 15 cm curb, terrain), two 12 m building facades, parked cars (4.4 m boxes in alternate 30 m
/// stretches), the swept surface of moving cars in the oncoming lane (60 m traces every 150 m)
/// and 4 isolated voxels in the air (what the K-nearest filter should drop).
void buildStreet(lidar::SemanticVoxelMap& map, std::size_t target) {
  auto put = [&](int x, int y, int z, LidarClass c) {
    lidar::Voxel v{};
    v.key = lidar::packKey({x, y, z});
    for (int k = 0; k < kNumLidarClasses; ++k) v.log_prob[k] = std::log(0.1f / 7);
    v.log_prob[static_cast<int>(c)] = std::log(0.9f);
    v.observations = 3;
    v.label = static_cast<uint8_t>(c);
    map.insertVoxel(v);
  };
  uint32_t rng = 12345;
  auto rnd = [&](int n) { return static_cast<int>((rng = rng * 1664525u + 1013904223u) >> 8) % n; };
  for (int x = 0; map.size() < target; ++x) {
    for (int y = -300; y < 300; ++y) {
      const int a = std::abs(y);
      put(x, y,
          a < 100   ? 0
          : a < 160 ? 3
                    : 4,
          a < 100   ? LidarClass::kRoad
          : a < 160 ? LidarClass::kSidewalk
                    : LidarClass::kVegetation);
    }
    for (int z = 5; z < 245; ++z) {
      put(x, -300, z, LidarClass::kBuilding);
      put(x, 299, z, LidarClass::kBuilding);
    }
    const int in_car = x % 120;  // 4.4 m car + 1.6 m gap
    if ((x / 600) % 2 == 0 && in_car < 88) {
      for (int y = -95; y < -60; ++y) put(x, y, 30, LidarClass::kVehicle);
      for (int z = 4; z < 30; ++z) {
        put(x, -95, z, LidarClass::kVehicle);
        put(x, -61, z, LidarClass::kVehicle);
        if (in_car == 0 || in_car == 87)
          for (int y = -94; y < -61; ++y) put(x, y, z, LidarClass::kVehicle);
      }
    }
    if (x % 3000 < 1200) {  // trace: the side and roof of cars passing in the left lane
      for (int y = 20; y < 55; ++y) put(x, y, 30, LidarClass::kVehicle);
      for (int z = 4; z < 30; ++z) put(x, 20, z, LidarClass::kVehicle);
    }
    for (int k = 0; k < 4; ++k)
      put(x, -250 + 10 * rnd(50), 60 + 10 * rnd(15), LidarClass::kVegetation);
  }
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app("lidar-semantic-map benchmark (one core)", "bench_lidar");
  std::string drive_dir, classifier_dir, kitti, model;
  std::vector<std::string> train_drives;
  std::size_t voxels = 10'000'000;
  int kitti_frames = 2;
  app.add_option("--drive", drive_dir, "simulate-lidar drive folder (timed)")->required();
  app.add_option("--train-drive", train_drives,
                 "labelled drive(s) to train the forests on, written to --classifier-dir");
  app.add_option("--classifier-dir", classifier_dir, "rtrees_<label>.yml folder");
  app.add_option("--voxels", voxels, "voxels of the synthetic refinement map")
      ->capture_default_str();
  app.add_option("--kitti", kitti, "KITTI raw drive for the ENet timing");
  app.add_option("--model", model, "ENet model (enet-model.net)");
  app.add_option("--kitti-frames", kitti_frames, "KITTI frames for the ENet timing")
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  setLogLevel(LogLevel::kWarn);
  omp_set_num_threads(1);
  cv::setNumThreads(1);
  std::printf("One core: omp_set_num_threads(1), cv::setNumThreads(1), num_threads = 1.\n\n");
  std::printf("| measurement | target | measured | met? |\n|---|---|---|---|\n");

  // (b) + (c) first, so that the peak-RSS baseline is the small process itself.
  const lidar::SemanticMapSettings p;  // lidar-semantic-map's defaults
  {
    const double rss0 = rssBytes(), peak0 = peakRssBytes();
    auto t = Clock::now();
    lidar::SemanticVoxelMap map(p.voxel_size, static_cast<float>(p.min_log_prob));
    buildStreet(map, voxels);
    const double t_build = since(t), n = static_cast<double>(map.size());
    const double peak_built = peakRssBytes(), acc_grown = map.memoryBytes() / n;
    map.shrinkToFit();
    const double acc_shrunk = map.memoryBytes() / n, peak_shrunk = peakRssBytes();
    const double rss_shrunk = rssBytes();
    row("synthetic street map (insertVoxel)", "&ge; 10 M voxels",
        fmt("%.0f voxels in %.1f s", n, t_build), n >= 1e7 ? "yes" : "**no**");
    row("memory: map accounting after shrinkToFit (voxel array + index)", "&le; 64 B/voxel",
        fmt("%.1f B/voxel (%.1f before shrink)", acc_shrunk, acc_grown),
        acc_shrunk <= 64 ? "yes" : "**no**");
    row("memory: peak-RSS delta (getrusage) building the map", "&le; 64 B/voxel",
        fmt("%.1f B/voxel (%.1f incl. shrinkToFit; current-RSS delta after it %.1f)",
            (peak_built - peak0) / n, (peak_shrunk - peak0) / n, (rss_shrunk - rss0) / n),
        (peak_built - peak0) / n <= 64 ? "yes" : "**no**");
    t = Clock::now();
    lidar::KnnFilterSettings ks = p.refinement.knn;
    const std::size_t before = map.size();
    map.filter(lidar::knnMeanDistanceFilter(map, ks, 1));
    const double t_knn = since(t);
    const std::size_t knn_removed = before - map.size();
    t = Clock::now();
    lidar::VehicleTraceStats ts;
    map.filter(lidar::vehicleTraceFilter(map, p.refinement.traces, &ts));
    const double t_tr = since(t);
    row("refinement: K-nearest filter (K = 6, 0.20 m) + vehicle-trace removal", "&le; 10 s",
        fmt("%.2f s (KNN %.2f s, traces %.2f s)", t_knn + t_tr, t_knn, t_tr),
        t_knn + t_tr <= 10 ? "yes" : "**no**");
    row("refinement: removed", "-",
        fmt("KNN %.0f isolated voxels; traces %.0f of %.0f vehicle voxels (%.0f clusters)",
            double(knn_removed), double(ts.removed_voxels), double(ts.vehicle_voxels),
            double(ts.clusters)),
        "-");
  }

  // (a) Per-frame labelling on the simulated drive, scans and semantics preloaded.
  const io::KittiRawDrive drive = io::openKittiRawDrive(drive_dir, {});
  auto poses = lidar::oxtsVeloPoses(drive, false);
  lidar::recenter(poses);
  const auto& fset = p.fusion;
  lidar::FrameSemantics semantics(drive, p.semantics);
  std::vector<io::VelodyneScan> scans;
  std::vector<io::SemanticImage> sems;
  double points = 0;
  for (const auto& f : drive.frames) {
    scans.push_back(io::readVelodyneBin(f.velodyne));
    sems.push_back(semantics.get(f));
    points += static_cast<double>(scans.back().size());
  }
  const double nf = static_cast<double>(drive.frames.size());
  lidar::ClusterClassifier forests;
  std::string em_note = "no classifier given: error minimisation skipped";
  if (!train_drives.empty() && !classifier_dir.empty()) {
    const auto t = Clock::now();
    std::vector<fs::path> td(train_drives.begin(), train_drives.end());
    const auto tr = lidar::trainClusterClassifier(td, {}, {}, p, lidar::RTreesSettings{}, "");
    tr.classifier.save(classifier_dir);
    em_note = fmt("forests trained in the bench on %.0f labelled frames of another seed (%.1f s)",
                  static_cast<double>(tr.frames_used), since(t));
  }
  if (!classifier_dir.empty()) {
    forests = lidar::ClusterClassifier::load(classifier_dir);
    if (train_drives.empty()) em_note = "forests loaded from " + classifier_dir;
  }
  const auto P = lidar::ImageProjection::of(drive.calib);
  for (int with_em = 0; with_em <= (forests.empty() ? 0 : 1); ++with_em) {
    const lidar::ClusterClassifier none;
    const lidar::ClusterClassifier& cls = with_em ? forests : none;
    lidar::SemanticVoxelMap map(p.voxel_size, static_cast<float>(p.min_log_prob));
    double t_all = 0, t_pr = 0, t_em = 0, t_fu = 0, projected = 0, clusters = 0, rejected = 0;
    for (std::size_t i = 0; i < scans.size(); ++i)  // untimed warm-up pass (page faults, caches)
      lidar::fuseFrame(map, scans[i].points, poses[i], P, sems[i], cls, fset);
    map = lidar::SemanticVoxelMap(p.voxel_size, static_cast<float>(p.min_log_prob));
    for (std::size_t i = 0; i < scans.size(); ++i) {
      const auto t = Clock::now();
      const auto st = lidar::fuseFrame(map, scans[i].points, poses[i], P, sems[i], cls, fset);
      t_all += since(t);
      t_pr += st.t_projection;
      t_em += st.t_error_min;
      t_fu += st.t_fusion;
      projected += static_cast<double>(st.projected);
      clusters += static_cast<double>(st.error_min.clusters);
      rejected += static_cast<double>(st.error_min.rejected_clusters);
    }
    const double fps = nf / t_all;
    row(with_em ? "per frame: projection + clustering + forests + fusion (no network)"
                : "per frame: projection + fusion, error minimisation skipped (no network)",
        "&ge; 30 frames/s", fmt("%.1f frames/s (%.1f ms/frame)", fps, 1e3 / fps),
        fps >= 30 ? "yes" : "**no**");
    row("  split per frame (ms): projection / error minimisation / fusion", "-",
        fmt("%.1f / %.1f / %.1f", 1e3 * t_pr / nf, 1e3 * t_em / nf, 1e3 * t_fu / nf), "-");
    if (with_em)
      row("  clusters per frame (rejected)", "-", fmt("%.0f (%.0f)", clusters / nf, rejected / nf),
          "-");
    else
      row("  input", "-",
          fmt("%.0f frames, %.0f points/scan, %.0f projected (5-50 m, in image_02); %.0f voxels",
              nf, points / nf, projected / nf, double(map.size())),
          "-");
  }
  row("error minimisation", "-", em_note, "-");

  // LiDAR odometry on every frame of the real KITTI drive, sweeps preloaded (the stage reads one
  // .bin per frame first: ~1 ms), default settings, one core; median of 3 passes.
  if (!kitti.empty() && fs::is_directory(kitti)) {
    const io::KittiRawDrive kd = io::openKittiRawDrive(kitti, {});
    std::vector<std::vector<Eigen::Vector3f>> sweeps;
    for (const auto& f : kd.frames) sweeps.push_back(io::readVelodyneBin(f.velodyne).points);
    std::vector<double> rates, cpu_rates;
    int untrusted = 0;
    for (int pass = 0; pass < 3; ++pass) {
      lidar::ScanOdometry odo(lidar::OdometrySettings{});
      untrusted = 0;
      const auto t = Clock::now();
      const double c = threadCpuSeconds();
      for (const auto& sw : sweeps) untrusted += !odo.add(sw, 0.1).trusted();
      rates.push_back(static_cast<double>(sweeps.size()) / since(t));
      cpu_rates.push_back(static_cast<double>(sweeps.size()) / (threadCpuSeconds() - c));
    }
    std::sort(rates.begin(), rates.end());
    std::sort(cpu_rates.begin(), cpu_rates.end());
    // The verdict is on CPU time: what one core does when it is not shared (the wall rate under
    // the load of the other jobs is shown beside it).
    row("LiDAR odometry (ScanOdometry::add), real KITTI sweeps", "&ge; 20 scans/s on one core",
        fmt("%.1f scans/s per CPU second of the thread, %.1f scans/s wall (medians of 3; %.0f "
            "sweeps, %.0f untrusted)",
            cpu_rates[1], rates[1], double(sweeps.size()), double(untrusted)),
        cpu_rates[1] >= 20 ? "yes" : "**no**");
  }

  // With the network: ENet on real KITTI frames (identity poses: no OXTS in every drive).
  if (kitti.empty() || model.empty() || !fs::exists(model) || !fs::is_directory(kitti)) {
    row("with ENet", "-", "skipped: KITTI drive or ENet model absent", "-");
    return 0;
  }
  lidar::SemanticMapSettings pk;
  pk.semantics.segmenter = "enet";
  pk.semantics.model = model;
  const io::KittiRawDrive kd = io::openKittiRawDrive(kitti, io::FrameRange{0, kitti_frames - 1, 1});
  lidar::FrameSemantics enet(kd, pk.semantics);
  const auto& kset = pk.fusion;
  lidar::SemanticVoxelMap kmap(pk.voxel_size, static_cast<float>(pk.min_log_prob));
  double t_net = 0, t_lab = 0;
  for (const auto& f : kd.frames) {
    const auto scan = io::readVelodyneBin(f.velodyne);
    auto t = Clock::now();
    const auto sem = enet.get(f);
    t_net += since(t);
    t = Clock::now();
    lidar::fuseFrame(kmap, scan.points, Pose3::Identity(), lidar::ImageProjection::of(kd.calib),
                     sem, forests, kset);
    t_lab += since(t);
  }
  const double nk = static_cast<double>(kd.frames.size());
  row("with ENet: network (incl. PNG decode) + labelling, real KITTI frames", "- (paper ~3.6 Hz)",
      fmt("%.2f frames/s (network %.2f s/frame, labelling %.1f ms/frame, %.0f frames)",
          nk / (t_net + t_lab), t_net / nk, 1e3 * t_lab / nk, nk),
      "-");
  return 0;
}
