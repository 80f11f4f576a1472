// Benchmark: mapfuse::fusion GICP vs PCL's GeneralizedIterativeClosestPoint on consecutive KITTI
// odometry scans (same voxelisation, same max correspondence distance). Prints a Markdown table
// (time per pair, step length, difference to poses/00.txt and between the two methods).
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/registration/gicp.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include "mapfuse/core/paths.hpp"
#include "mapfuse/fusion/gicp.hpp"

using namespace mapfuse;
using Clock = std::chrono::steady_clock;

namespace {
fusion::Cloud loadScan(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw std::runtime_error("cannot read " + path);
  fusion::Cloud c;
  float v[4];
  while (f.read(reinterpret_cast<char*>(v), sizeof(v))) c.points.emplace_back(v[0], v[1], v[2]);
  return c;
}
Pose3 readRow(const std::string& line) {
  std::istringstream is(line);
  Pose3 T = Pose3::Identity();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) is >> T.matrix()(r, c);
  return T;
}
double seconds(Clock::time_point a) {
  return std::chrono::duration<double>(Clock::now() - a).count();
}
double rotDeg(const Pose3& a, const Pose3& b) {
  return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle() * 180.0 / M_PI;
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app("GICP vs PCL GICP on KITTI odometry scans");
  std::string seq = (mapfuse::sharedRoot() / "data/kitti_odometry").string();
  double voxel = 0.25, max_corr = 1.0;
  int frames = 6, repeats = 3;
  app.add_option("--kitti", seq, "kitti_odometry folder")->capture_default_str();
  app.add_option("--voxel", voxel, "voxel size [m]")->capture_default_str();
  app.add_option("--max-corr", max_corr, "max correspondence distance [m]")->capture_default_str();
  app.add_option("--frames", frames, "scans to use")->capture_default_str();
  app.add_option("--repeats", repeats, "timing repeats (median kept)")->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  // Calibration Tr (velo -> cam0) and camera-frame poses -> velodyne-frame relative poses.
  Pose3 Tr = Pose3::Identity();
  {
    std::ifstream f(seq + "/sequences/00/calib.txt");
    std::string line;
    while (std::getline(f, line))
      if (line.rfind("Tr:", 0) == 0) Tr = readRow(line.substr(3));
  }
  std::vector<Pose3> poses;
  {
    std::ifstream f(seq + "/poses/00.txt");
    std::string line;
    while (std::getline(f, line) && int(poses.size()) < frames) poses.push_back(readRow(line));
  }
  std::vector<fusion::Cloud> clouds;
  for (int i = 0; i < frames; ++i) {
    char name[64];
    std::snprintf(name, sizeof(name), "/sequences/00/velodyne/%06d.bin", i);
    clouds.push_back(fusion::voxelDownsample(loadScan(seq + name), voxel));
  }

  std::printf(
      "| pair | points | mapfuse 1 thr [s] | mapfuse 2 thr [s] | PCL [s] | speed-up (1 thr) "
      "| step mapfuse [m] | step PCL [m] | step poses.txt [m] | mapfuse-PCL [m / deg] "
      "| mapfuse-poses [m / deg] | PCL-poses [m / deg] |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  double sum_ours = 0, sum_pcl = 0;
  for (int i = 0; i + 1 < frames; ++i) {
    const Pose3 T_gt = Tr.inverse() * poses[i].inverse() * poses[i + 1] * Tr;
    auto runOurs = [&](int threads, Pose3& T) {
      std::vector<double> t;
      for (int r = 0; r < repeats; ++r) {
        const auto t0 = Clock::now();
        fusion::Cloud src = clouds[i + 1], tgt = clouds[i];
        fusion::estimateCovariances(src, 10, 1.0);
        fusion::estimateCovariances(tgt, 10, 1.0);
        fusion::GicpSettings s;
        s.max_correspondence_distance = max_corr;
        s.num_threads = threads;
        s.max_iterations = 64;
        const fusion::GicpTarget target(std::move(tgt), std::max(1.0, max_corr));
        T = fusion::alignGicp(target, src, Pose3::Identity(), s).T_target_source;
        t.push_back(seconds(t0));
      }
      std::sort(t.begin(), t.end());
      return t[t.size() / 2];
    };
    Pose3 T_ours, T_ours2;
    const double t1 = runOurs(1, T_ours), t2 = runOurs(2, T_ours2);

    pcl::PointCloud<pcl::PointXYZ>::Ptr src(new pcl::PointCloud<pcl::PointXYZ>),
        tgt(new pcl::PointCloud<pcl::PointXYZ>);
    for (const auto& p : clouds[i + 1].points) src->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
    for (const auto& p : clouds[i].points) tgt->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
    std::vector<double> tp;
    Pose3 T_pcl = Pose3::Identity();
    for (int r = 0; r < repeats; ++r) {
      const auto t0 = Clock::now();
      pcl::GeneralizedIterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ> gicp;
      gicp.setInputSource(src);
      gicp.setInputTarget(tgt);
      gicp.setMaxCorrespondenceDistance(max_corr);
      gicp.setMaximumIterations(64);
      gicp.setTransformationEpsilon(1e-8);
      pcl::PointCloud<pcl::PointXYZ> out;
      gicp.align(out);
      T_pcl.matrix() = gicp.getFinalTransformation().cast<double>();
      tp.push_back(seconds(t0));
    }
    std::sort(tp.begin(), tp.end());
    const double t_pcl = tp[tp.size() / 2];
    sum_ours += t1;
    sum_pcl += t_pcl;
    auto d = [](const Pose3& a, const Pose3& b) {
      char buf[64];
      std::snprintf(buf, sizeof(buf), "%.3f / %.3f", (a.translation() - b.translation()).norm(),
                    rotDeg(a, b));
      return std::string(buf);
    };
    std::printf(
        "| %d-%d | %zu | %.3f | %.3f | %.3f | %.1fx | %.3f | %.3f | %.3f | %s | %s | %s |\n", i,
        i + 1, clouds[i + 1].size(), t1, t2, t_pcl, t_pcl / t1, T_ours.translation().norm(),
        T_pcl.translation().norm(), T_gt.translation().norm(), d(T_ours, T_pcl).c_str(),
        d(T_ours, T_gt).c_str(), d(T_pcl, T_gt).c_str());
  }
  std::printf("\nTotal: mapfuse %.3f s, PCL %.3f s, speed-up %.1fx (single thread each)\n",
              sum_ours, sum_pcl, sum_pcl / sum_ours);
  return 0;
}
