// KITTI odometry poses files (12 numbers a line), both readers: lidar-semantic-map's and
// lsm-build's (--poses).
#include "fuzz_support.hpp"
#include "mapfuse/io/bounds.hpp"
#include "mapfuse/io/drive_frames.hpp"
#include "mapfuse/io/kitti_poses.hpp"

using namespace mapfuse;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const std::string text = fuzz::bytesOf(data, size);
  std::vector<Pose3> a, b;
  const bool ok_a = fuzz::accepts([&] { a = io::parseKittiOdometryPoses(text, "poses.txt"); });
  const bool ok_b = fuzz::accepts([&] { b = io::parseKittiPoses(text, "poses.txt"); });
  for (const auto& T : a) MAPFUSE_FUZZ_CHECK(T.matrix().allFinite());
  for (const auto& T : b) MAPFUSE_FUZZ_CHECK(T.matrix().allFinite());
  // The two readers agree on what a poses file is (lsm-build's also refuses an empty file).
  if (ok_b) MAPFUSE_FUZZ_CHECK(ok_a && a.size() == b.size());
  if (ok_a && !a.empty()) {
    // Written and read again: the same translations within the %.9e text precision.
    io::writeKittiOdometryPoses(fuzz::scratchDir() / "poses.txt", a);
    const auto back = io::readKittiOdometryPoses(fuzz::scratchDir() / "poses.txt");
    MAPFUSE_FUZZ_CHECK(back.size() == a.size());
    for (std::size_t i = 0; i < a.size(); ++i)
      MAPFUSE_FUZZ_CHECK((back[i].translation() - a[i].translation()).norm() <=
                         1e-8 * (1.0 + a[i].translation().norm()));
  }
  return 0;
}
