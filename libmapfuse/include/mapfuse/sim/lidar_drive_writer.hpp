#pragma once
/// @file A simulated LiDAR drive written frame by frame in the KITTI raw layout
/// (docs/lidar-ground-truth.md): per frame the Velodyne scan, its SemanticKITTI labels, image_02,
/// the network's class probabilities, the true image labels and the OXTS record; at the end the
/// timestamp files, the OXTS data format and the true Velodyne poses.
#include <filesystem>
#include <string>
#include <vector>

#include "mapfuse/io/kitti_raw_writer.hpp"
#include "mapfuse/sim/lidar_drive.hpp"

namespace mapfuse::sim {

class LidarDriveWriter {
 public:
  /// @param drive_dir the drive's folder (io::kittiDriveDir)
  /// @param start_time s of frame 0 on the drive's date; `dt` s between frames
  LidarDriveWriter(std::filesystem::path drive_dir, std::string date, double start_time, double dt,
                   const io::MercatorAnchor& anchor);

  /// @brief Writes the files of frame `k` and remembers its stamps and true pose.
  void add(int k, const LidarFrame& frame);

  /// @brief Writes the timestamp files, oxts/dataformat.txt and ground_truth/poses_world_velo.txt.
  void finish() const;

 private:
  std::filesystem::path dir_;
  std::string date_;
  double start_time_, dt_;
  io::MercatorAnchor anchor_;
  std::vector<std::string> stamps_, starts_, ends_, poses_;
};

}  // namespace mapfuse::sim
