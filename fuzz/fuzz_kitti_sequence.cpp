// KITTI odometry / SemanticKITTI sequence folders (docs/kitti.md), as evaluate voxels and
// lidar-semantic-map open them: the input's parts (lines "====" between them) become a folder
// in the scratch space, then the sequence is opened (openKittiRawDrive: calib.txt, times.txt,
// the scans listed), its poses.txt turned into Velodyne poses, and each scan with its labels
// made into truth voxels (evaluate voxels' path (a), camera field of view on). Parts:
//   0 calib.txt   1 times.txt   2 poses.txt   3 image_2/000000.png (its header gives the size)
//   4, 6, 8, 10: velodyne/00000k.bin   5, 7, 9, 11: labels/00000k.label
// An empty part is an absent file. Refusals: exit 3, or 4 for a file the folder lacks (no
// calib.txt, a scan without its labels). Accepted: times finite, within the timestamp bound and
// never going back; poses finite, within the coordinate bound.
#include <cmath>

#include "fuzz_support.hpp"
#include "mapfuse/eval/voxel_truth.hpp"
#include "mapfuse/io/bounds.hpp"
#include "mapfuse/io/kitti_raw.hpp"
#include "mapfuse/io/semantic_kitti.hpp"
#include "mapfuse/io/velodyne.hpp"
#include "mapfuse/lidar/drive_poses.hpp"

using namespace mapfuse;
namespace fs = std::filesystem;

namespace {
constexpr std::size_t kFrames = 4;
const std::initializer_list<ExitCode> kRefusals = {ExitCode::kBadInput, ExitCode::kIo};

fs::path makeSequence(const std::vector<std::string>& parts) {
  const fs::path dir = fuzz::scratchDir() / "sequence";
  fs::remove_all(dir);
  fs::create_directories(dir / "velodyne");
  fs::create_directories(dir / "labels");
  fs::create_directories(dir / "image_2");
  const char* names[] = {"calib.txt", "times.txt", "poses.txt", "image_2/000000.png"};
  for (std::size_t i = 0; i < 4 && i < parts.size(); ++i)
    if (!parts[i].empty()) fuzz::writeFile(dir / names[i], parts[i]);
  for (std::size_t k = 0; k < kFrames; ++k) {
    const std::string stem = "00000" + std::to_string(k);
    if (4 + 2 * k < parts.size() && !parts[4 + 2 * k].empty())
      fuzz::writeFile(dir / "velodyne" / (stem + ".bin"), parts[4 + 2 * k]);
    if (5 + 2 * k < parts.size() && !parts[5 + 2 * k].empty())
      fuzz::writeFile(dir / "labels" / (stem + ".label"), parts[5 + 2 * k]);
  }
  return dir;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const fs::path dir = makeSequence(fuzz::splitParts(fuzz::bytesOf(data, size), 4 + 2 * kFrames,
                                                     /*binary=*/true));
  io::KittiRawDrive drive;
  if (!fuzz::accepts([&] { drive = io::openKittiRawDrive(dir, io::FrameRange{}); }, kRefusals))
    return 0;
  MAPFUSE_FUZZ_CHECK(drive.layout == "sequence" && !drive.frames.empty());
  for (std::size_t k = 0; k < drive.frames.size(); ++k) {
    const double t = drive.frames[k].timestamp;
    if (std::isnan(t)) continue;
    MAPFUSE_FUZZ_CHECK(std::abs(t) <= io::bounds::kMaxStamp);
    if (k > 0) MAPFUSE_FUZZ_CHECK(!(t < drive.frames[k - 1].timestamp));
  }
  std::vector<Pose3> poses(drive.frames.size(), Pose3::Identity());
  if (!drive.poses_file.empty() &&
      !fuzz::accepts([&] { poses = lidar::veloPosesFromFile(drive, drive.poses_file); }, kRefusals))
    return 0;
  MAPFUSE_FUZZ_CHECK(poses.size() == drive.frames.size());
  for (const Pose3& T : poses) {
    MAPFUSE_FUZZ_CHECK(T.matrix().allFinite());
    MAPFUSE_FUZZ_CHECK(T.translation().cwiseAbs().maxCoeff() <= 2 * io::bounds::kMaxCoordinate);
  }
  // Truth voxels as evaluate voxels builds them (0.2 m voxels, 5-50 m, image_02's view).
  eval::VoxelTruth truth(0.2);
  const Eigen::Matrix<double, 3, 4> P2 = drive.calib.veloToImage2();
  std::size_t points = 0;
  for (std::size_t k = 0; k < drive.frames.size(); ++k) {
    io::VelodyneScan scan;
    std::vector<uint32_t> labels;
    if (!fuzz::accepts([&] { scan = io::readVelodyneBin(drive.frames[k].velodyne); }, kRefusals) ||
        !fuzz::accepts(
            [&] {
              labels =
                  io::readSemanticKittiLabels(dir / "labels" / (drive.frames[k].name + ".label"));
            },
            kRefusals))
      return 0;
    if (labels.size() != scan.size()) return 0;  // evaluate voxels: InputError naming the file
    points += scan.size();
    if (!fuzz::accepts([&] {
          eval::addLabelledScan(truth, scan.points, labels, poses[k], 5.0, 50.0, &P2,
                                drive.calib.image_width, drive.calib.image_height);
        }))
      return 0;
  }
  MAPFUSE_FUZZ_CHECK(truth.size() <= points);
  return 0;
}
