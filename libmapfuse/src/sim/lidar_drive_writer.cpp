#include "mapfuse/sim/lidar_drive_writer.hpp"

#include <cstdio>
#include <utility>

#include "mapfuse/io/atomic_file.hpp"
#include "mapfuse/io/semantic_image.hpp"
#include "mapfuse/io/semantic_kitti.hpp"
#include "mapfuse/io/velodyne.hpp"
#include "mapfuse/sim/lidar_camera.hpp"

namespace mapfuse::sim {
namespace {
namespace fs = std::filesystem;

/// A 3x4 pose as a line of KITTI's poses files (row-major, full precision).
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

LidarDriveWriter::LidarDriveWriter(fs::path drive_dir, std::string date, double start_time,
                                   double dt, const io::MercatorAnchor& anchor)
    : dir_(std::move(drive_dir)),
      date_(std::move(date)),
      start_time_(start_time),
      dt_(dt),
      anchor_(anchor) {}

void LidarDriveWriter::add(int k, const LidarFrame& f) {
  const std::string name = io::kittiFrameName(k);
  io::VelodyneScan vs;
  vs.points.reserve(f.scan.points.size());
  vs.reflectance.reserve(f.scan.points.size());
  for (const auto& p : f.scan.points) {
    vs.points.emplace_back(p.head<3>());
    vs.reflectance.push_back(p.w());
  }
  const CameraFrame& cam = f.camera;
  io::writeVelodyneBin(dir_ / "velodyne_points" / "data" / (name + ".bin"), vs);
  io::writeSemanticKittiLabels(dir_ / "labels" / (name + ".label"), f.scan.labels);
  io::writePngBgr(dir_ / "image_02" / "data" / (name + ".png"), cam.width, cam.height,
                  shadeLabels(cam));
  io::writeSemanticImage(io::semanticsDir(dir_) / (name + ".prob"), f.probabilities);
  io::writeSemanticImage(dir_ / "ground_truth" / "label_02" / (name + ".png"),
                         io::SemanticImage::fromLabels(cam.width, cam.height, cam.labels));
  const geo::OxtsRecord rec = oxtsRecord(f.T_world_imu, f.T_world_imu_next, dt_, anchor_);
  io::writeLines(dir_ / "oxts" / "data" / (name + ".txt"), {io::formatOxtsLine(rec)});
  const double t = start_time_ + f.time;
  stamps_.push_back(io::formatKittiTimestamp(date_, t));
  starts_.push_back(io::formatKittiTimestamp(date_, t - 0.5 * dt_));
  ends_.push_back(io::formatKittiTimestamp(date_, t + 0.5 * dt_));
  poses_.push_back(poseLine(f.T_world_velo));
}

void LidarDriveWriter::finish() const {
  io::writeLines(dir_ / "image_02" / "timestamps.txt", stamps_);
  io::writeLines(dir_ / "velodyne_points" / "timestamps.txt", stamps_);
  io::writeLines(dir_ / "velodyne_points" / "timestamps_start.txt", starts_);
  io::writeLines(dir_ / "velodyne_points" / "timestamps_end.txt", ends_);
  io::writeLines(dir_ / "oxts" / "timestamps.txt", stamps_);
  io::writeOxtsDataformat(dir_ / "oxts" / "dataformat.txt");
  io::writeLines(dir_ / "ground_truth" / "poses_world_velo.txt", poses_);
}

}  // namespace mapfuse::sim
